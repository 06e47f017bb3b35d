// The backward pass one step at a time (diff/StepBackward.h): stepping it by hand gives the whole
// pass's gradient bit for bit, and one step's vector-Jacobian product matches central finite
// differences of that step for the start state and for a parameter, in the wind and on the
// incline (every node slipping: through the contact adjoint).

#include "DiffTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/StepBackward.h>
#include <weft/diff/TaskLoss.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

#include <random>

namespace weft {
namespace {

using test::TempDir;

BackwardSettings direct() {
  BackwardSettings s;
  s.method = "direct";
  return s;
}

TEST(StepBackward, SteppedByHandIsTheWholePassBitForBit) {
  TempDir dir;
  const Scene scene = test::windTaskScene(dir, {"wind.strength", "cloths.0.material.stretch"});
  const ForwardPass pass = runForwardPass(scene);
  const TaskLoss loss(scene);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  const GradientResult whole =
      backpropagate(pass.trajectory, loss, parameters, scene.solver.backward);
  StepBackward back(pass.trajectory, parameters, scene.solver.backward);
  std::vector<NodeMatrix> dLdx = loss.gradient(pass.trajectory);
  const int m = pass.trajectory.nodeCount();
  NodeMatrix dLdv1 = NodeMatrix::Zero(m, 3), dLdv0(m, 3);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(parameters.size());
  for (int n = pass.trajectory.stepCount() - 1; n >= 0; --n) {
    back.step(n, dLdx[n + 1], dLdv1, dLdx[n], dLdv0, gradient);
    dLdv1 = dLdv0;
  }
  back.addInitial(dLdv1, gradient);
  EXPECT_EQ(gradient, whole.gradient);
  EXPECT_EQ(dLdx[0], whole.dLdx0);
  EXPECT_EQ(dLdv1, whole.dLdv0);
  EXPECT_EQ(back.stats().solves, whole.solver.solves);
}

// One step n of `scene` (forward solver tight): for random weights wx, wv and the linear
// function l = wx . x_{n+1} + wv . v_{n+1}, StepBackward's dl/dx_n, dl/dv_n and dl/dtheta against
// central differences of the step from a perturbed start or parameter.
void expectStepMatchesFiniteDifferences(const Scene& scene, int n,
                                        const std::vector<std::string>& paths, double tolerance) {
  const ForwardPass pass = runForwardPass(scene);
  ASSERT_EQ(pass.unconvergedSteps, 0);
  const Trajectory& t = pass.trajectory;
  const ParameterSet parameters = ParameterSet::fromPaths(scene, paths);
  const int m = t.nodeCount();
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto randomMatrix = [&] {
    NodeMatrix a(m, 3);
    for (int i = 0; i < m; ++i)
      for (int c = 0; c < 3; ++c) a(i, c) = uniform(random);
    return a;
  };
  const NodeMatrix wx = randomMatrix(), wv = randomMatrix();
  StepBackward back(t, parameters, direct());
  NodeMatrix dLdx0 = NodeMatrix::Zero(m, 3), dLdv0(m, 3);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(parameters.size());
  back.step(n, wx, wv, dLdx0, dLdv0, gradient);

  // l after one step from (x, v) with the model `model`.
  auto stepped = [&](const std::shared_ptr<const Model>& model, const NodeMatrix& x,
                     const NodeMatrix& v) {
    Simulator sim(model);
    sim.restart(n, x, v);
    sim.step();
    return (wx.array() * sim.positions().array()).sum() +
           (wv.array() * sim.velocities().array()).sum();
  };
  const NodeMatrix dx = randomMatrix(), dv = randomMatrix();
  const double eps = 1e-6;
  const NodeMatrix& x = t.positions[n];
  const NodeMatrix& v = t.velocities[n];
  const double fdX =
      (stepped(t.model, x + eps * dx, v) - stepped(t.model, x - eps * dx, v)) / (2 * eps);
  const double fdV =
      (stepped(t.model, x, v + eps * dv) - stepped(t.model, x, v - eps * dv)) / (2 * eps);
  EXPECT_NEAR((dLdx0.array() * dx.array()).sum(), fdX, tolerance * std::abs(fdX));
  EXPECT_NEAR((dLdv0.array() * dv.array()).sum(), fdV, tolerance * std::abs(fdV));
  const Eigen::VectorXd values = parameters.values(scene);
  for (int k = 0; k < parameters.size(); ++k) {
    // A relative step of 1e-4: below it the forward solves' round-off shows (measured: stretch
    // agrees to 3e-8 at 1e-4, 5e-5 at 1e-6).
    const double h = 1e-4 * std::max(std::abs(values[k]), 1.0);
    Eigen::VectorXd up = values, down = values;
    up[k] += h, down[k] -= h;
    const double fd = (stepped(parameters.compile(scene, up), x, v) -
                       stepped(parameters.compile(scene, down), x, v)) /
                      (2 * h);
    EXPECT_NEAR(gradient[k], fd, tolerance * std::abs(fd) + 1e-9) << paths[k];
  }
}

TEST(StepBackward, OneStepMatchesFiniteDifferencesInTheWind) {
  const Scene scene = withTightForwardSolver(test::parse(test::windClothScene(6, 12)), 1e-10);
  expectStepMatchesFiniteDifferences(scene, 7, {"wind.strength", "cloths.0.material.stretch"},
                                     1e-5);
}

TEST(StepBackward, OneStepMatchesFiniteDifferencesThroughSlidingContact) {
  const Scene scene = withTightForwardSolver(test::parse(test::inclineScene()), 1e-10);
  expectStepMatchesFiniteDifferences(scene, 10, {"obstacles.0.friction", "gravity.2"}, 1e-4);
}

}  // namespace
}  // namespace weft
