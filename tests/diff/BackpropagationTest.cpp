// The adjoint gradient (DiffCloth Sec. 4.1) against central finite differences of the task loss
// on a small cloth hanging in wind, for every kind of parameter the adjoint supports, and the
// initial-state gradients.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

using test::TempDir;

const std::vector<std::string> kAllParameters = {
    "cloths.0.material.stretch",   "cloths.0.material.bend",      "cloths.0.material.density",
    "wind.strength",               "wind.direction.0",            "wind.direction.2",
    "wind.frequency",              "wind.phase",                  "cloths.0.initial_velocity.0",
    "cloths.0.initial_velocity.2", "cloths.0.forces.0.force.1",   "cloths.0.forces.0.force.2",
    "gravity.1"};

TEST(Backpropagation, MatchesCentralFiniteDifferencesForEveryParameterKind) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, kAllParameters);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  ASSERT_EQ(parameters.size(), static_cast<int>(kAllParameters.size()));
  test::expectAdjointMatchesFiniteDifferences(scene);
}

TEST(Backpropagation, FinalFrameLossOnChosenVertices) {
  TempDir dir;
  nlohmann::json doc = test::windClothScene(6, 20);
  nlohmann::json targetDoc = doc;
  targetDoc["cloths"][0]["material"]["density"] = 0.12;
  const std::string target = test::writeTargetTrajectory(targetDoc, dir.file("final.npy"));
  test::addTask(doc, "final", target, {"cloths.0.material.density", "wind.phase", "cloths.0.material.stretch"});
  doc["task"]["loss"]["final"]["vertices"] = {42, 45, 48};
  doc["task"]["loss"]["final"]["weight"] = 10.0;
  const Scene scene = test::parse(doc);
  const GradientCheckReport report = checkGradient(scene, ParameterSet::fromTask(scene), {});
  for (const GradientCheckEntry& e : report.entries) {
    SCOPED_TRACE(e.param);
    EXPECT_LT(e.relativeError, 1e-4) << "adjoint " << e.adjoint << " fd " << e.finiteDifference;
  }
}

TEST(Backpropagation, InitialVelocityGradientIsTheSumOfTheNodalOnes) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, {"cloths.0.initial_velocity.2"}, 10);
  const Scene tight = withTightForwardSolver(scene, 1e-8);
  const ForwardPass pass = runForwardPass(tight);
  const TaskLoss loss(tight);
  const GradientResult g = backpropagate(tight, pass.trajectory, loss, ParameterSet::fromTask(tight),
                                         tight.solver.backward);
  EXPECT_NEAR(g.gradient[0], g.dLdv0.col(2).sum(), 1e-12 * std::abs(g.gradient[0]));
  EXPECT_EQ(g.solver.solves, 10);
}

}  // namespace
}  // namespace weft
