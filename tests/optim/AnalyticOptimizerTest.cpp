// All four optimisers through the same Optimizer interface on analytic objectives: a bounded
// quadratic (minimum inside and outside the box) and Rosenbrock's valley; bounds, budgets,
// evaluation caps, determinism, and which kind of evaluation each method asks for (L-BFGS-B and
// Adam gradients, CMA-ES and the (1+1)-ES values alone).

#include <optim/AnalyticObjectives.h>

#include <weft/optim/Optimizer.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

using test::kInf;
using test::Quadratic;
using test::Rosenbrock;

const char* const kMethods[] = {"lbfgsb", "adam", "cmaes", "es1p1"};
const char* const kEvolutionStrategies[] = {"cmaes", "es1p1"};

bool gradientFree(const std::string& method) {
  return method == "cmaes" || method == "es1p1";
}

std::unique_ptr<Optimizer> make(const std::string& method, OptimizerSettings s) {
  auto o = makeOptimizer(method, s);
  EXPECT_TRUE(o) << method;
  return o;
}

// Settings under which each method reaches the analytic minima below: Adam needs a small step
// and many iterations, the evolution strategies many (cheap) evaluations.
OptimizerSettings settingsFor(const std::string& method) {
  OptimizerSettings s;
  if (method == "adam") {
    s.learningRate = 0.02;
    s.maxEvaluations = 20000;
    s.gradientTolerance = 1e-7;
  } else if (method == "cmaes") {
    s.maxEvaluations = 6000;
  } else if (method == "es1p1") {
    s.maxEvaluations = 60000;
  }
  return s;
}

// How close each method gets to the minimum under settingsFor (the tests' tolerances).
double tolerance(const std::string& method) {
  return method == "adam" ? 1e-4 : 1e-6;
}

bool inside(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  return (x.array() >= lower.array()).all() && (x.array() <= upper.array()).all();
}

TEST(AnalyticOptimizer, EveryMethodFindsTheQuadraticMinimumInsideTheBox) {
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Quadratic f(Eigen::Vector3d(0.3, -1.2, 2.0), Eigen::Vector3d(1.0, 10.0, 100.0));
    auto o = make(method, settingsFor(method));
    const auto r = o->minimize(f, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::Constant(-5),
                               Eigen::Vector3d::Constant(5));
    EXPECT_NEAR(r.x[0], 0.3, tolerance(method)) << r.stopReason;
    EXPECT_NEAR(r.x[1], -1.2, tolerance(method)) << r.stopReason;
    EXPECT_NEAR(r.x[2], 2.0, tolerance(method)) << r.stopReason;
    // A gradient evaluation costs 10 nominal steps here, a value alone 5.
    EXPECT_EQ(r.steps, (gradientFree(method) ? 5LL : 10LL) * r.evaluations);
    EXPECT_EQ(o->log().entries().size(), static_cast<std::size_t>(r.evaluations));
    if (method == "lbfgsb") {
      EXPECT_LT(r.loss, 1e-10);
      EXPECT_LT(r.evaluations, 50);
    }
  }
}

TEST(AnalyticOptimizer, MinimumOutsideTheBoxLandsOnTheBound) {
  // The unconstrained minimum (3, -2) lies outside [-1, 1]^2: the constrained one is the corner
  // (1, -1), and no evaluated point may leave the box.
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Quadratic f(Eigen::Vector2d(3.0, -2.0), Eigen::Vector2d(1.0, 4.0));
    auto o = make(method, settingsFor(method));
    const Eigen::Vector2d lower(-1, -1), upper(1, 1);
    const auto r = o->minimize(f, Eigen::Vector2d(0.2, 0.5), lower, upper);
    EXPECT_NEAR(r.x[0], 1.0, 1e-9) << r.stopReason;
    EXPECT_NEAR(r.x[1], -1.0, 1e-9) << r.stopReason;
    for (const LogEntry& e : o->log().entries())
      EXPECT_TRUE(inside(e.x, lower, upper)) << e.x.transpose();
    if (!gradientFree(method)) {
      EXPECT_LT(r.projectedGradientNorm, 1e-6);
    }
  }
}

TEST(AnalyticOptimizer, EveryMethodSolvesRosenbrock) {
  // L-BFGS-B unbounded; the others in [-2, 2]^2 (Adam needs a box for its projection to mean
  // anything; the evolution strategies scale their first step to it).
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Rosenbrock f;
    OptimizerSettings s = settingsFor(method);
    double tol = 1e-5;
    if (method == "lbfgsb") s.gradientTolerance = 1e-9;
    if (method == "adam") s.learningRate = 0.01, s.maxEvaluations = 50000, tol = 2e-3;
    auto o = make(method, s);
    const double bound = method == "lbfgsb" ? kInf : 2.0;
    const auto r = o->minimize(f, Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d::Constant(-bound),
                               Eigen::Vector2d::Constant(bound));
    EXPECT_NEAR(r.x[0], 1.0, tol) << r.stopReason << ", " << r.evaluations << " evaluations";
    EXPECT_NEAR(r.x[1], 1.0, 2.0 * tol) << r.stopReason << ", " << r.evaluations << " evaluations";
    if (method == "lbfgsb") {
      EXPECT_LT(r.evaluations, 200);
    }
  }
}

TEST(AnalyticOptimizer, BoundedRosenbrockStopsOnTheBound) {
  // With x <= 0.5 the constrained minimum is at x = 0.5, y = 0.25.
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Rosenbrock f;
    OptimizerSettings s = settingsFor(method);
    if (method == "adam") s.maxEvaluations = 50000, s.learningRate = 0.01;
    auto o = make(method, s);
    const Eigen::Vector2d lower(-2, -2), upper(0.5, 2);
    const auto r = o->minimize(f, Eigen::Vector2d(-1.2, 1.0), lower, upper);
    EXPECT_NEAR(r.x[0], 0.5, 1e-6) << r.stopReason;
    EXPECT_NEAR(r.x[1], 0.25, 1e-3) << r.stopReason;
    for (const LogEntry& e : o->log().entries())
      EXPECT_TRUE(inside(e.x, lower, upper)) << e.x.transpose();
  }
}

TEST(AnalyticOptimizer, BudgetAndEvaluationCapStopBeforeExceeding) {
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Rosenbrock r0;
    Quadratic f(Eigen::Vector2d(3.0, -2.0), Eigen::Vector2d(1.0, 1000.0));
    OptimizerSettings s;
    s.budget = 75;  // 7 gradient evaluations of 10 steps fit (the 8th would not), or 15 values of 5
    s.gradientTolerance = 0.0;
    auto o = make(method, s);
    const auto r =
        o->minimize(f, Eigen::Vector2d(0, 0), Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5));
    EXPECT_EQ(r.stopReason, "budget");
    EXPECT_EQ(r.evaluations, gradientFree(method) ? 15 : 7);
    EXPECT_EQ(r.steps, gradientFree(method) ? 75 : 70);
    for (const LogEntry& e : o->log().entries()) EXPECT_LE(e.steps, s.budget);
    OptimizerSettings capped;
    capped.maxEvaluations = 5;
    capped.gradientTolerance = 0.0;
    auto o2 = make(method, capped);
    const auto r2 =
        o2->minimize(r0, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    EXPECT_EQ(r2.stopReason, "max evaluations");
    EXPECT_EQ(r2.evaluations, 5);
    // The result is the best point logged, not the last one tried.
    for (const LogEntry& e : o2->log().entries()) EXPECT_GE(e.loss, r2.loss);
  }
}

TEST(AnalyticOptimizer, SameSeedSameLog) {
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    OptimizerSettings s = settingsFor(method);
    s.seed = 7;
    s.maxEvaluations = 300;
    Rosenbrock f1, f2;
    auto a = make(method, s), b = make(method, s);
    const auto ra =
        a->minimize(f1, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    const auto rb =
        b->minimize(f2, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    ASSERT_EQ(a->log().entries().size(), b->log().entries().size());
    for (std::size_t i = 0; i < a->log().entries().size(); ++i) {
      EXPECT_EQ(a->log().entries()[i].loss, b->log().entries()[i].loss);
      EXPECT_EQ(a->log().entries()[i].x, b->log().entries()[i].x);
      EXPECT_EQ(a->log().entries()[i].steps, b->log().entries()[i].steps);
    }
    EXPECT_EQ(ra.x, rb.x);
    EXPECT_EQ(ra.stopReason, rb.stopReason);
  }
}

TEST(AnalyticOptimizer, EvolutionStrategiesFollowTheirSeed) {
  // Both start at the given point (the first evaluation), then sample from their own stream.
  for (const std::string method : kEvolutionStrategies) {
    SCOPED_TRACE(method);
    OptimizerSettings s = settingsFor(method);
    s.maxEvaluations = 40;
    Rosenbrock f;
    s.seed = 1;
    auto a = make(method, s);
    a->minimize(f, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    s.seed = 2;
    auto b = make(method, s);
    b->minimize(f, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    const auto& ea = a->log().entries();
    const auto& eb = b->log().entries();
    ASSERT_EQ(ea.size(), 40u);
    ASSERT_EQ(eb.size(), 40u);
    EXPECT_EQ(ea[0].x, Eigen::Vector2d(-1.2, 1.0));
    EXPECT_EQ(ea[0].x, eb[0].x);
    for (std::size_t i = 1; i < ea.size(); ++i)
      EXPECT_NE(ea[i].x, eb[i].x) << "evaluation " << i + 1;
  }
}

TEST(AnalyticOptimizer, GradientFreeMethodsAskForValuesOnly) {
  for (const std::string method : kMethods) {
    SCOPED_TRACE(method);
    Quadratic inner(Eigen::Vector2d(0.5, -0.5), Eigen::Vector2d(1.0, 3.0));
    test::CountingObjective f(inner);
    OptimizerSettings s;
    s.maxEvaluations = 30;
    auto o = make(method, s);
    EXPECT_EQ(o->usesGradient(), !gradientFree(method));
    const auto r =
        o->minimize(f, Eigen::Vector2d(0, 0), Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
    EXPECT_EQ(f.gradients + f.values, r.evaluations);
    EXPECT_EQ(gradientFree(method) ? f.gradients : f.values, 0);
    EXPECT_EQ(r.hasGradient, !gradientFree(method));
    for (const LogEntry& e : o->log().entries()) {
      EXPECT_EQ(e.hasGradient, !gradientFree(method));
      EXPECT_EQ(e.gradient.size(), gradientFree(method) ? 0 : 2);
      EXPECT_GE(e.seconds, 0.0);
    }
    // Wall-clock seconds are cumulative.
    for (std::size_t i = 1; i < o->log().entries().size(); ++i)
      EXPECT_GE(o->log().entries()[i].seconds, o->log().entries()[i - 1].seconds);
  }
}

}  // namespace
}  // namespace weft
