// The semismooth Newton contact solve (solver.contact = "newton", Simulator::solveContactNewton)
// solves the fixed point of DiffCloth's PD contact iteration (Eqs. 10-12): on DiffCloth's Slope
// scene, where the PD iteration converges every step, both must reach the same trajectory, and
// Newton must get there with far fewer solves with P (that is its reason to exist). On a cloth
// settling on a sphere, where Newton hands stalled steps to the PD iteration, it must still keep
// nodes out of the sphere and every converged step's contacts in their branches.

#include "ContactTestSupport.h"

#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

namespace weft {
namespace {

nlohmann::json slopeScene(const char* contactMethod) {
  std::ifstream in(WEFT_ASSET_DIR "/scenes/slope.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["cloths"][0]["mesh"]["grid"]["resolution"] = {12, 12};
  doc["solver"]["contact"] = contactMethod;
  doc["solver"]["pd_tolerance"] = 1e-6;
  doc["solver"]["pd_iterations"] = 2000;  // enough for the PD iteration to converge every step
  return doc;
}

TEST(NewtonContact, SlopeMatchesThePdIterationWithFewerSolves) {
  const int steps = 40;
  const test::ContactRun pd = test::runScene(slopeScene("pd"), steps);
  const test::ContactRun newton = test::runScene(slopeScene("newton"), steps);
  int pdSolves = 0, newtonSolves = 0;
  for (int n = 1; n <= steps; ++n) {
    ASSERT_TRUE(pd.trajectory.steps[n - 1].converged) << "pd, step " << n;
    ASSERT_TRUE(newton.trajectory.steps[n - 1].converged) << "newton, step " << n;
    pdSolves += pd.trajectory.steps[n - 1].pdIterations;
    newtonSolves += newton.trajectory.steps[n - 1].pdIterations;
    // Both stop at a residual below 1e-6 m/s^2 (mass-weighted RMS); over a step that moves a
    // node by h^2 times that, and the two trajectories' differences accumulate over the steps.
    EXPECT_LT((pd.trajectory.positions[n] - newton.trajectory.positions[n]).cwiseAbs().maxCoeff(),
              1e-7)
        << "step " << n;
    const StepContacts& a = pd.trajectory.contacts[n - 1];
    const StepContacts& b = newton.trajectory.contacts[n - 1];
    ASSERT_EQ(a.points.size(), b.points.size()) << "step " << n;
    for (std::size_t k = 0; k < a.points.size(); ++k) {
      ASSERT_EQ(a.points[k].branch, b.points[k].branch) << "step " << n << " contact " << k;
      EXPECT_EQ(test::branchViolation(b.points[k], 1e-6), "")
          << "step " << n << " node " << b.points[k].node;
    }
  }
  EXPECT_GT(newton.trajectory.steps.back().slip, 0) << "the ribbon must be sliding";
  RecordProperty("pd_solves", std::to_string(pdSolves));
  RecordProperty("newton_solves", std::to_string(newtonSolves));
  EXPECT_LT(3 * newtonSolves, pdSolves) << "pd " << pdSolves << " solves, newton " << newtonSolves;
}

// The ribbon lands on the slope within its first steps: every node changes branch at once, and
// the damped Newton steps before the full one that switches them barely lower the residual. That
// is not a stalled attempt (a full step converges two iterations later); giving up on it there
// would split the step, which on the scene's 24^2 ribbon once cost more than the whole rest of the
// run. With adaptive time stepping on (the default), every step must be solved whole.
TEST(NewtonContact, SlopeLandingIsSolvedWithoutSplittingTheStep) {
  std::ifstream in(WEFT_ASSET_DIR "/scenes/slope.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  ASSERT_GT(doc["solver"].value("max_halvings", 6), 0);
  const int steps = 20;
  const test::ContactRun run = test::runScene(doc, steps);
  int landed = 0;
  for (int n = 1; n <= steps; ++n) {
    const StepStats& s = run.trajectory.steps[n - 1];
    EXPECT_TRUE(s.converged) << "step " << n;
    EXPECT_EQ(s.substeps, 1) << "step " << n << " was split";
    landed = std::max(landed, s.stick + s.slip);
  }
  EXPECT_EQ(landed, run.trajectory.model->nodeCount()) << "every node must touch the slope";
}

TEST(NewtonContact, SphereDropStaysOutsideAndConvergedStepsObeyTheLaw) {
  constexpr double kRadius = 0.4, kSkin = 1e-3;
  nlohmann::json doc =
      test::clothScene(0.8, 12, Vec3(0.0, kRadius + 0.05, 0.0), 0.01, 500.0, 1e-3, 0.2);
  test::addObstacle(doc, "sphere", {{"center", {0, 0, 0}}, {"radius", kRadius}}, 0.5);
  doc["obstacles"][0]["thickness"] = kSkin;
  doc["solver"]["contact"] = "newton";
  doc["solver"]["pd_iterations"] = 400;
  const test::ContactRun run = test::runScene(doc, 60);
  const Trajectory& t = run.trajectory;
  int converged = 0, active = 0;
  for (int n = 1; n <= t.stepCount(); ++n) {
    ASSERT_TRUE(t.positions[n].allFinite());
    if (!t.steps[n - 1].converged) continue;
    ++converged;
    // A converged step has its contacts' velocities right; the frame is frozen at detection, so a
    // node sliding over the curved surface may dip by about travel^2 / (2 R) below it (1 mm).
    EXPECT_GT(t.positions[n].rowwise().norm().minCoeff() - kRadius - kSkin, -1e-3) << "step " << n;
    for (const ContactPoint& p : t.contacts[n - 1].points) {
      ASSERT_EQ(test::branchViolation(p, 1e-3), "")
          << "step " << n << " node " << p.node << " " << branchName(p.branch);
      active += p.branch != ContactBranch::TakeOff;
    }
  }
  RecordProperty("converged_steps", std::to_string(converged));
  EXPECT_GT(active, 0) << "no converged step had an active contact";
  EXPECT_GE(converged, 30) << "of 60 steps";
}

}  // namespace
}  // namespace weft
