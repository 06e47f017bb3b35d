// The adjoint gradient (DiffCloth Sec. 4.1) against central finite differences of the task loss
// on a small cloth hanging in wind, for every kind of parameter the adjoint supports, and the
// initial-state gradients.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

#include <stdexcept>

namespace weft {
namespace {

using test::TempDir;

const std::vector<std::string> kAllParameters = {"cloths.0.material.stretch",
                                                 "cloths.0.material.bend",
                                                 "cloths.0.material.density",
                                                 "wind.strength",
                                                 "wind.direction.0",
                                                 "wind.direction.2",
                                                 "wind.frequency",
                                                 "wind.phase",
                                                 "cloths.0.initial_velocity.0",
                                                 "cloths.0.initial_velocity.2",
                                                 "cloths.0.forces.0.force.1",
                                                 "cloths.0.forces.0.force.2",
                                                 "gravity.1"};

TEST(Backpropagation, MatchesCentralFiniteDifferencesForEveryParameterKind) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, kAllParameters);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  ASSERT_EQ(parameters.size(), static_cast<int>(kAllParameters.size()));
  test::expectAdjointMatchesFiniteDifferences(scene);
}

TEST(Backpropagation, GradcheckReportsTheTightAdjointGradient) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, {"wind.strength", "cloths.0.material.stretch"}, 8);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  const GradientCheckOptions options;
  const TightAdjointGradient tight = tightAdjointGradient(scene, parameters, options);
  EXPECT_EQ(tight.scene.solver.pdTolerance, options.forwardTolerance);
  EXPECT_EQ(tight.backward.tolerance, options.backwardTolerance);
  // The adjoint column of gradcheck (and weft.gradient in Python) is this gradient, bit for bit.
  const GradientCheckReport report = checkGradient(scene, parameters, options);
  EXPECT_EQ(report.loss, tight.result.loss);
  ASSERT_EQ(report.entries.size(), 2u);
  for (int k = 0; k < 2; ++k) EXPECT_EQ(report.entries[k].adjoint, tight.result.gradient[k]);
}

TEST(Backpropagation, FinalFrameLossOnChosenVertices) {
  TempDir dir;
  nlohmann::json doc = test::windClothScene(6, 20);
  nlohmann::json targetDoc = doc;
  targetDoc["cloths"][0]["material"]["density"] = 0.12;
  const std::string target = test::writeTargetTrajectory(targetDoc, dir.file("final.npy"));
  test::addTask(doc, "final", target,
                {"cloths.0.material.density", "wind.phase", "cloths.0.material.stretch"});
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
  const GradientResult g =
      backpropagate(pass.trajectory, loss, ParameterSet::fromTask(tight), tight.solver.backward);
  EXPECT_NEAR(g.gradient[0], g.dLdv0.col(2).sum(), 1e-12 * std::abs(g.gradient[0]));
  EXPECT_EQ(g.solver.solves, 10);
}

// The backward pass differentiates the model the run was simulated with, which the trajectory
// carries; a trajectory without one (read back from a run folder) is refused, not guessed at.
TEST(Backpropagation, DifferentiatesTheModelItsTrajectoryCarries) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, {"wind.strength"}, 6);
  const ForwardPass pass = runForwardPass(scene);
  ASSERT_NE(pass.trajectory.model, nullptr);
  EXPECT_EQ(pass.trajectory.model->scene().name, scene.name);
  const TaskLoss loss(scene);
  const GradientResult g =
      backpropagate(pass.trajectory, loss, ParameterSet::fromTask(scene), scene.solver.backward);
  EXPECT_NE(g.gradient[0], 0.0);
  Trajectory readBack = pass.trajectory;
  readBack.model.reset();
  EXPECT_THROW(backpropagate(readBack, loss, ParameterSet::fromTask(scene), scene.solver.backward),
               std::invalid_argument);
}

// The passes report every step (a progress display; SimulationObjective passes it on), in order,
// and a report that throws abandons the pass (how the editor cancels within an evaluation).
TEST(Backpropagation, PassesReportEveryStepAndStopWhenTheReportThrows) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, {"wind.strength"}, 6);
  std::vector<std::pair<int, int>> forward, backward;
  const ForwardPass pass =
      runForwardPass(scene, [&](PassPhase phase, int number, int done, int total) {
        EXPECT_EQ(phase, PassPhase::Forward);
        EXPECT_EQ(number, 1);
        forward.emplace_back(done, total);
      });
  const int steps = scene.time.steps;
  ASSERT_EQ(static_cast<int>(forward.size()), steps);
  for (int k = 0; k < steps; ++k) EXPECT_EQ(forward[k], std::make_pair(k + 1, steps));
  const TaskLoss loss(scene);
  backpropagate(
      pass.trajectory, loss, ParameterSet::fromTask(scene), scene.solver.backward,
      [&](PassPhase phase, int number, int done, int total) {
        EXPECT_EQ(phase, PassPhase::Backward);
        EXPECT_EQ(number, 2);
        backward.emplace_back(done, total);
      },
      2);
  ASSERT_EQ(static_cast<int>(backward.size()), steps);
  for (int k = 0; k < steps; ++k) EXPECT_EQ(backward[k], std::make_pair(k + 1, steps));

  struct Stop {};
  int heard = 0;
  EXPECT_THROW(runForwardPass(scene,
                              [&](PassPhase, int, int done, int) {
                                ++heard;
                                if (done == 3) throw Stop{};
                              }),
               Stop);
  EXPECT_EQ(heard, 3) << "no step after the throw";
}

// dL/dx_n at an intermediate state against central differences: state n's positions moved
// (velocities held) and the run continued from there by Simulator::restart.
TEST(Backpropagation, StateGradientMatchesFiniteDifferencesMidRun) {
  TempDir dir;
  const Scene scene =
      withTightForwardSolver(test::windTaskScene(dir, {"wind.strength"}, 12), 1e-10);
  const ForwardPass pass = runForwardPass(scene);
  const TaskLoss loss(scene);
  BackwardSettings exact = scene.solver.backward;
  exact.method = "direct";  // per-vertex values: the default 1e-4 solve tolerance shows in them
  const GradientResult g =
      backpropagate(pass.trajectory, loss, ParameterSet::fromTask(scene), exact);
  ASSERT_EQ(g.dLdx.size(), pass.trajectory.positions.size());
  EXPECT_EQ(g.dLdx[0], g.dLdx0);
  const int n = 6;
  auto lossFrom = [&](const NodeMatrix& xn) {
    Simulator sim(scene);
    sim.restart(n, xn, pass.trajectory.velocities[n]);
    Trajectory rest;
    sim.run(scene.time.steps - n, rest);
    Trajectory whole = pass.trajectory;
    whole.positions[std::size_t(n)] = xn;  // the loss looks at state n too
    for (int k = 1; k < static_cast<int>(rest.positions.size()); ++k) {
      whole.positions[std::size_t(n + k)] = rest.positions[std::size_t(k)];
      whole.velocities[std::size_t(n + k)] = rest.velocities[std::size_t(k)];
    }
    return loss.value(scene, whole);
  };
  const double eps = 1e-6;
  for (const auto& [node, axis] : {std::pair{44, 0}, std::pair{48, 2}, std::pair{10, 1}}) {
    NodeMatrix plus = pass.trajectory.positions[n], minus = plus;
    plus(node, axis) += eps;
    minus(node, axis) -= eps;
    const double fd = (lossFrom(plus) - lossFrom(minus)) / (2 * eps);
    const double adjoint = g.dLdx[n](node, axis);
    EXPECT_NEAR(adjoint, fd, 1e-4 * std::abs(fd) + 1e-9) << "node " << node << " axis " << axis;
  }
}

}  // namespace
}  // namespace weft
