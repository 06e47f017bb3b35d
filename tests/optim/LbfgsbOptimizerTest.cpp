// L-BFGS-B's own iteration (optim/LbfgsbOptimizer.h): with the default settings it is LBFGSpp's
// LBFGSBSolver evaluation for evaluation (bit-equal points), --first-step sets the length of the
// first trial step, and --min-curvature-step keeps short steps' curvature pairs out of the BFGS
// matrix (all of them, in the limit: steepest descent).

#include <optim/AnalyticObjectives.h>

#include <weft/optim/Optimizer.h>

#include <LBFGSB.h>

#include <gtest/gtest.h>

#include <vector>

namespace weft {
namespace {

using test::Quadratic;
using test::Rosenbrock;

// The points LBFGSpp's own solver evaluates, with the parameters LbfgsbOptimizer gives it.
std::vector<Eigen::VectorXd> lbfgsppPoints(Objective& f, Eigen::VectorXd x,
                                           const Eigen::VectorXd& lower,
                                           const Eigen::VectorXd& upper,
                                           const OptimizerSettings& s) {
  LBFGSpp::LBFGSBParam<double> param;
  param.epsilon = s.gradientTolerance;
  param.epsilon_rel = 0.0;
  param.past = 1;
  param.delta = s.lossTolerance;
  param.max_iterations = s.maxIterations;
  LBFGSpp::LBFGSBSolver<double> solver(param);
  std::vector<Eigen::VectorXd> points;
  auto record = [&](const Eigen::VectorXd& at, Eigen::VectorXd& g) {
    points.push_back(at);
    return f.evaluate(at, g);
  };
  double fx = 0.0;
  try {
    solver.minimize(record, x, fx, lower, upper);
  } catch (const std::exception&) {
    // A line search that gives up ends the run in both.
  }
  return points;
}

void expectSamePoints(Objective& f, const Eigen::VectorXd& x0, const Eigen::VectorXd& lower,
                      const Eigen::VectorXd& upper) {
  OptimizerSettings s;
  const std::vector<Eigen::VectorXd> theirs = lbfgsppPoints(f, x0, lower, upper, s);
  auto o = makeOptimizer("lbfgsb", s);
  o->minimize(f, x0, lower, upper);
  const auto& ours = o->log().entries();
  ASSERT_GT(theirs.size(), 5u);
  ASSERT_EQ(ours.size(), theirs.size());
  for (std::size_t k = 0; k < ours.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(ours[k].x, theirs[k]);
  }
}

TEST(LbfgsbOptimizer, DefaultsReproduceLbfgsppEvaluationForEvaluation) {
  Rosenbrock rosenbrock;
  expectSamePoints(rosenbrock, Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(-2.0, -2.0),
                   Eigen::Vector2d(2.0, 2.0));
  // Active bounds: the bowl's centre lies outside the box in two of four coordinates.
  Quadratic bowl(Eigen::Vector4d(0.3, 3.0, -2.5, 0.1), Eigen::Vector4d(1.0, 10.0, 100.0, 3.0));
  expectSamePoints(bowl, Eigen::Vector4d::Zero(), Eigen::Vector4d::Constant(-1.0),
                   Eigen::Vector4d::Constant(1.0));
}

TEST(LbfgsbOptimizer, FirstStepIsTheLengthOfTheFirstTrialStep) {
  for (const double first : {1.0, 0.01}) {
    SCOPED_TRACE(first);
    Quadratic bowl(Eigen::Vector3d(0.3, -1.2, 2.0), Eigen::Vector3d(1.0, 10.0, 100.0));
    OptimizerSettings s;
    s.lbfgsbFirstStep = first;
    auto o = makeOptimizer("lbfgsb", s);
    const auto r = o->minimize(bowl, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(-5.0),
                               Eigen::Vector3d::Constant(5.0));
    const auto& log = o->log().entries();
    ASSERT_GE(log.size(), 2u);
    EXPECT_NEAR((log[1].x - log[0].x).norm(), first, 1e-14);
    // Either way the line search and the quasi-Newton steps reach the minimum.
    EXPECT_LT(r.loss, 1e-10) << r.stopReason;
  }
}

TEST(LbfgsbOptimizer, MinCurvatureStepKeepsShortStepsOutOfTheMatrix) {
  // Keeping no pair at all leaves the identity: steepest descent with a line search, which
  // zig-zags down the anisotropic bowl; with its pairs L-BFGS-B needs a handful of evaluations.
  Quadratic bowl(Eigen::Vector3d(0.3, -1.2, 2.0), Eigen::Vector3d(1.0, 10.0, 100.0));
  OptimizerSettings s;
  s.maxEvaluations = 400;
  auto quasiNewton = makeOptimizer("lbfgsb", s);
  const auto a =
      quasiNewton->minimize(bowl, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(-5.0),
                            Eigen::Vector3d::Constant(5.0));
  s.lbfgsbMinCurvatureStep = 1e9;
  auto steepest = makeOptimizer("lbfgsb", s);
  const auto b = steepest->minimize(bowl, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(-5.0),
                                    Eigen::Vector3d::Constant(5.0));
  EXPECT_LT(a.loss, 1e-10);
  EXPECT_LT(a.evaluations, 20);
  EXPECT_GT(b.evaluations, 3 * a.evaluations) << b.stopReason << " " << b.loss;
  // A threshold below every step the run takes changes nothing.
  s.lbfgsbMinCurvatureStep = 1e-12;
  auto same = makeOptimizer("lbfgsb", s);
  const auto c = same->minimize(bowl, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(-5.0),
                                Eigen::Vector3d::Constant(5.0));
  EXPECT_EQ(c.evaluations, a.evaluations);
  EXPECT_EQ(c.x, a.x);
}

}  // namespace
}  // namespace weft
