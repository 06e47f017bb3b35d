// A cloth pinned at two corners settles to a static equilibrium: the implicit-Euler equations
// (DiffCloth Eq. 3) hold at the final state, internal and external forces balance, the cloth
// is at rest, and a softer cloth sags further.

#include "PhysicsTestSupport.h"

#include <support/SceneBuilder.h>

#include <gtest/gtest.h>

#include <algorithm>

namespace weft {
namespace {

constexpr double kSize = 0.4;  // m
constexpr int kQuads = 6;
constexpr double kDt = 0.02;  // s
constexpr int kSteps = 300;   // 6 s: the kick below dies out in about 1 s
constexpr int kQuietWindow = 50;

struct Settled {
  double stepResidual;  // Eq. 3 residual of the last step, m/s^2 (mass-weighted RMS)
  double forceBalance;  // f_ext - grad W(x) at the final state, m/s^2 (mass-weighted RMS)
  double quietSpeed;    // largest node speed over the last kQuietWindow steps, m/s
  double sag;           // drop of the lowest point from its initial height, m
  double topSag;        // drop of the midpoint of the top edge, m
};

Settled settle(double stretch, const std::string& method) {
  // Bending keeps the flat hanging state stable: with almost none, the slack region between
  // the pins buckles out of plane (a real instability, seeded by round-off) and takes long to
  // settle.
  nlohmann::json doc = test::hangingClothScene(kSize, kQuads, kDt, 0, stretch, 1e-3, 0.1);
  doc["solver"] = {{"method", method}, {"pd_iterations", 5000}, {"pd_tolerance", 1e-9}};
  // An in-plane kick, so the cloth has to come to rest rather than start there.
  doc["cloths"][0]["initial_velocity"] = {0.3, 0.2, 0.0};
  const Scene scene = test::parse(doc);
  Simulator sim(scene);
  const NodeMatrix initial = sim.positions();
  Settled s{};
  NodeMatrix x0, v0;
  for (int n = 1; n <= kSteps; ++n) {
    x0 = sim.positions();
    v0 = sim.velocities();
    sim.step();
    if (n > kSteps - kQuietWindow)
      s.quietSpeed = std::max(s.quietSpeed, test::maxSpeed(sim.velocities()));
  }
  const NodeMatrix& x = sim.positions();
  const Eigen::VectorXd& mass = sim.cloth().mass;
  s.stepResidual = test::massWeightedRms(test::stepResidual(sim, x0, v0, x, sim.time()), mass);
  s.forceBalance = test::massWeightedRms(
      test::externalForces(sim, sim.time()) - test::energyGradient(sim, x), mass);
  s.sag = initial.col(1).minCoeff() - x.col(1).minCoeff();
  s.topSag = initial(kQuads / 2, 1) - x(kQuads / 2, 1);
  return s;
}

// Both forward solvers must reach the same kind of equilibrium.
class Equilibrium : public ::testing::TestWithParam<std::string> {};

TEST_P(Equilibrium, PinnedClothSettlesWhereForcesBalance) {
  const Settled s = settle(200.0, GetParam());
  RecordProperty("step_residual", std::to_string(s.stepResidual));
  RecordProperty("force_balance", std::to_string(s.forceBalance));
  // The solver stops each step at 1e-9 m/s^2; the recorded state is one PD step further on.
  EXPECT_LT(s.stepResidual, 1e-6);
  // At rest the inertia term vanishes: the cloth and the pins carry gravity (9.8 m/s^2) alone.
  EXPECT_LT(s.forceBalance, 1e-6);
  EXPECT_LT(s.quietSpeed, 1e-8);
  EXPECT_GT(s.sag, 0.0);
  EXPECT_GT(s.topSag, 0.0);
}

TEST_P(Equilibrium, SofterClothSagsFurther) {
  const Settled stiff = settle(400.0, GetParam());
  const Settled soft = settle(40.0, GetParam());
  EXPECT_LT(stiff.quietSpeed, 1e-8);
  EXPECT_LT(soft.quietSpeed, 1e-8);
  EXPECT_LT(soft.forceBalance, 1e-6);
  EXPECT_GT(soft.sag, stiff.sag);
  EXPECT_GT(soft.topSag, stiff.topSag);
  // Small strains: the sag scales roughly like 1 / stiffness (a factor 10 here).
  EXPECT_GT(soft.sag, 5.0 * stiff.sag) << "stiff " << stiff.sag << " m, soft " << soft.sag << " m";
}

INSTANTIATE_TEST_SUITE_P(Solvers, Equilibrium, ::testing::Values("newton", "pd"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace weft
