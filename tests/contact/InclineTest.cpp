// A ribbon lying on a plane under gravity tilted by theta (equivalently, on an incline): it
// sticks when mu > tan(theta) and slides with acceleration g (sin theta - mu cos theta) when
// mu < tan(theta). Every node is in one contact with the same frame, the ribbon moves rigidly,
// and implicit Euler then gives v_n = n h a exactly, so the measured acceleration must match
// Coulomb's law to the solver tolerance. All three contact solvers (solver.contact) are checked.

#include "ContactTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

struct InclineCase {
  const char* name;
  double thetaDeg, mu;
};

void PrintTo(const InclineCase& c, std::ostream* os) {
  *os << c.name;
}

class Incline : public ::testing::TestWithParam<InclineCase> {};

void checkIncline(const InclineCase& c, const char* contactMethod) {
  const double g = 9.8, theta = c.thetaDeg * M_PI / 180.0, h = 0.01, skin = 1e-3;
  const int steps = 40;
  nlohmann::json doc = test::clothScene(0.4, 8, Vec3(0, skin, 0), h);
  doc["cloths"][0]["mesh"]["grid"] = {{"size", {0.4, 0.1}}, {"resolution", {8, 2}}};
  doc["gravity"] = {g * std::sin(theta), -g * std::cos(theta), 0.0};
  doc["solver"] = {{"pd_iterations", 200}, {"pd_tolerance", 1e-6}, {"contact", contactMethod}};
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, c.mu);
  doc["obstacles"][0]["thickness"] = skin;
  const test::ContactRun run = test::runScene(doc, steps);
  const Trajectory& t = run.trajectory;
  const NodeMatrix& x0 = t.positions.front();

  for (int n = 1; n <= steps; ++n) {
    ASSERT_TRUE(t.steps[n - 1].converged) << "step " << n;
    // Never into the plane, never lifted off it.
    ASSERT_NEAR(t.positions[n].col(1).minCoeff(), skin, 1e-9) << "step " << n;
    ASSERT_NEAR(t.positions[n].col(1).maxCoeff(), skin, 1e-9) << "step " << n;
    for (const ContactPoint& p : t.contacts[n - 1].points)
      ASSERT_EQ(test::branchViolation(p, 1e-9), "")
          << "step " << n << " node " << p.node << " " << branchName(p.branch);
  }
  const double expected = g * (std::sin(theta) - c.mu * std::cos(theta));
  const NodeMatrix& v = t.velocities.back();
  if (expected <= 0.0) {
    EXPECT_LT((t.positions.back() - x0).cwiseAbs().maxCoeff(), 1e-9) << "moved while stuck";
    EXPECT_LT(v.cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_EQ(t.steps.back().stick, run.sim->cloth().nodeCount());
  } else {
    // Rigid sliding along +X at v = a t.
    const double measured = v.col(0).mean() / (steps * h);
    EXPECT_NEAR(measured, expected, 0.01 * expected) << "measured " << measured << " m/s^2";
    EXPECT_LT((v.col(0).array() - v.col(0).mean()).abs().maxCoeff(), 1e-6 * v.col(0).mean());
    EXPECT_LT(v.col(2).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_EQ(t.steps.back().slip, run.sim->cloth().nodeCount());
    // Distance travelled: implicit Euler x_n = a h^2 n (n + 1) / 2.
    EXPECT_NEAR((t.positions.back().col(0) - x0.col(0)).mean(),
                expected * h * h * steps * (steps + 1) / 2,
                0.01 * expected * h * h * steps * steps / 2);
  }
}

TEST_P(Incline, SticksOrSlidesAsCoulombSays) {
  checkIncline(GetParam(), "pd");
}
// The same law through the experimental active-set Newton contact solve (ActiveContactSet.h).
TEST_P(Incline, ActiveSetSticksOrSlidesAsCoulombSays) {
  checkIncline(GetParam(), "active_set");
}
// ... and through the semismooth Newton solve of the same fixed point
// (Simulator::solveContactNewton).
TEST_P(Incline, NewtonSticksOrSlidesAsCoulombSays) {
  checkIncline(GetParam(), "newton");
}

INSTANTIATE_TEST_SUITE_P(Cases, Incline,
                         ::testing::Values(InclineCase{"Theta10Frictionless", 10, 0.0},
                                           InclineCase{"Theta10Mu02Sticks", 10, 0.2},
                                           InclineCase{"Theta20Mu02Slides", 20, 0.2},
                                           InclineCase{"Theta20Mu05Sticks", 20, 0.5},
                                           InclineCase{"Theta30Mu03Slides", 30, 0.3},
                                           InclineCase{"Theta30Mu07Sticks", 30, 0.7},
                                           InclineCase{"Theta45Mu09Slides", 45, 0.9},
                                           InclineCase{"Theta45Mu11Sticks", 45, 1.1},
                                           InclineCase{"Theta60Mu1000Sticks", 60, 1000.0}),
                         [](const ::testing::TestParamInfo<InclineCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace weft
