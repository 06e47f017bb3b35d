// Gaussian smoothing of an objective (optim/SmoothedObjective.h) on functions whose smoothed
// gradient is known in closed form: exact for a quadratic, the bump's gradient scaled by
// exp(-s^2 w^2 / 2) for x^2 + a (1 - cos(w x)), a sampling variance that falls as 1 / pairs and
// matches the spread over seeds, its costs, the box, and L-BFGS-B through it past the bumps.

#include <weft/optim/Optimizer.h>
#include <weft/optim/SmoothedObjective.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace weft {
namespace {

// f(x) = 1/2 x^T A x + b^T x.
class Quadratic final : public Objective {
 public:
  Quadratic() : a_(3, 3), b_(3) {
    a_ << 4, 1, 0, 1, 3, -1, 0, -1, 2;
    b_ << 1, -2, 0.5;
  }
  int dimension() const override { return 3; }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g = a_ * x + b_;
    return 0.5 * x.dot(a_ * x) + b_.dot(x);
  }
  long long stepsPerEvaluation() const override { return 7; }
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
};

// f(x) = x^2 + a (1 - cos(w x)), one variable: its one global minimum at 0 and, for a w^2 > 2,
// local ones where 2 x = -a w sin(w x).
class Bumpy final : public Objective {
 public:
  Bumpy(double a, double w) : a_(a), w_(w) {}
  int dimension() const override { return 1; }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    ++evaluations;
    g.resize(1);
    g[0] = 2.0 * x[0] + a_ * w_ * std::sin(w_ * x[0]);
    return x[0] * x[0] + a_ * (1.0 - std::cos(w_ * x[0]));
  }
  // The smoothed gradient: 2x + a w sin(w x) exp(-s^2 w^2 / 2).
  double smoothedGradient(double x, double s) const {
    return 2.0 * x + a_ * w_ * std::sin(w_ * x) * std::exp(-0.5 * s * s * w_ * w_);
  }
  double a_, w_;
  int evaluations = 0;
};

TEST(SmoothedObjective, IsExactForAQuadratic) {
  Quadratic f;
  SmoothedObjective smoothed(f, 0.7, 1, 3);
  Eigen::VectorXd x(3), g, exact;
  x << 0.3, -1.2, 2.0;
  smoothed.evaluate(x, g);
  f.evaluate(x, exact);
  EXPECT_LT((g - exact).norm(), 1e-12 * exact.norm()) << "a pair cancels the odd terms";
  EXPECT_EQ(smoothed.lastGradientVariance(), 0.0) << "one pair: no sample variance";
  SmoothedObjective many(f, 0.7, 8, 3);
  many.evaluate(x, g);
  EXPECT_LT((g - exact).norm(), 1e-12 * exact.norm());
  EXPECT_LT(many.lastGradientVariance(), 1e-24) << "every pair gives the same gradient";
}

TEST(SmoothedObjective, ScalesABumpsGradientByTheGaussiansFactor) {
  Bumpy f(0.1, 20.0);    // bumps 0.31 apart
  const double s = 0.1;  // exp(-2) = 0.135 of the bump's gradient is left
  SmoothedObjective smoothed(f, s, 2000, 11);
  for (double x0 : {0.37, -0.8, 1.3}) {
    Eigen::VectorXd x(1), g, raw;
    x[0] = x0;
    smoothed.evaluate(x, g);
    f.evaluate(x, raw);
    const double expected = f.smoothedGradient(x0, s);
    const double standardError = std::sqrt(smoothed.lastGradientVariance());
    EXPECT_NEAR(g[0], expected, 4.0 * standardError) << "x = " << x0;
    EXPECT_LT(standardError, 0.05) << "x = " << x0;
    EXPECT_GT(std::abs(raw[0] - expected), 10.0 * standardError)
        << "the raw gradient differs: the smoothing did something at x = " << x0;
  }
}

TEST(SmoothedObjective, VarianceFallsAsOneOverPairsAndMatchesTheSpreadOverSeeds) {
  Bumpy f(0.1, 20.0);
  Eigen::VectorXd x(1), g;
  x[0] = 0.37;
  const auto reported = [&](int pairs) {
    double mean = 0.0;
    for (unsigned seed = 0; seed < 20; ++seed) {
      SmoothedObjective smoothed(f, 0.1, pairs, seed);
      smoothed.evaluate(x, g);
      mean += smoothed.lastGradientVariance() / 20.0;
    }
    return mean;
  };
  const double v16 = reported(16), v256 = reported(256);
  EXPECT_GT(v16 / v256, 16.0 / 1.5);
  EXPECT_LT(v16 / v256, 16.0 * 1.5);
  // The reported variance against the estimates' spread over 200 seeds.
  double sum = 0.0, sumSquares = 0.0;
  const int seeds = 200;
  for (int seed = 0; seed < seeds; ++seed) {
    SmoothedObjective smoothed(f, 0.1, 16, 1000 + seed);
    smoothed.evaluate(x, g);
    sum += g[0], sumSquares += g[0] * g[0];
  }
  const double spread = (sumSquares - sum * sum / seeds) / (seeds - 1);
  EXPECT_GT(spread / v16, 0.6);
  EXPECT_LT(spread / v16, 1.6);
  EXPECT_NEAR(sum / seeds, f.smoothedGradient(0.37, 0.1), 4.0 * std::sqrt(spread / seeds))
      << "unbiased: the mean over seeds is the smoothed gradient";
}

TEST(SmoothedObjective, CostsTwoEvaluationsPerPairAndStaysInTheBox) {
  Quadratic f;
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(3, -0.1), upper = Eigen::VectorXd::Ones(3);
  SmoothedObjective smoothed(f, 10.0, 5, 1, lower, upper);
  EXPECT_EQ(smoothed.stepsPerEvaluation(), 2 * 5 * 7);
  // A recording objective: every point asked for lies in the box.
  class Recording final : public Objective {
   public:
    int dimension() const override { return 3; }
    double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
      lowest = std::min(lowest, x.minCoeff()), highest = std::max(highest, x.maxCoeff());
      ++calls;
      g = Eigen::VectorXd::Zero(3);
      return 0.0;
    }
    double lowest = 1e300, highest = -1e300;
    int calls = 0;
  } recording;
  SmoothedObjective boxed(recording, 10.0, 5, 1, lower, upper);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(3, 0.5), g;
  boxed.evaluate(x, g);
  boxed.value(x);
  EXPECT_EQ(recording.calls, 2 * 2 * 5);
  EXPECT_GE(recording.lowest, -0.1);
  EXPECT_LE(recording.highest, 1.0);
}

TEST(SmoothedObjective, LetsLbfgsbPassTheBumpsToTheBowlsBottom) {
  // From x = 1.3 the raw gradient leads L-BFGS-B into a local minimum between bumps; smoothed with
  // s = 0.1 the bumps are damped to 0.135 of their gradient, and what minima are left lie within
  // 0.135 of the global one at 0.
  Bumpy raw(0.1, 20.0);
  OptimizerSettings settings;
  settings.maxEvaluations = 60;
  Eigen::VectorXd x0(1), lower(1), upper(1);
  x0[0] = 1.3, lower[0] = -3.0, upper[0] = 3.0;
  const OptimizationResult plain =
      makeOptimizer("lbfgsb", settings)->minimize(raw, x0, lower, upper);
  EXPECT_GT(std::abs(plain.x[0]), 0.2) << "stuck between bumps (the case for smoothing)";
  Bumpy inner(0.1, 20.0);
  SmoothedObjective smoothed(inner, 0.1, 64, 5, lower, upper);
  const OptimizationResult result =
      makeOptimizer("lbfgsb", settings)->minimize(smoothed, x0, lower, upper);
  EXPECT_LT(std::abs(result.x[0]), 0.15) << "x = " << result.x[0];
}

}  // namespace
}  // namespace weft
