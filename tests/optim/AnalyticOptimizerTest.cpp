// Both optimisers through the same Optimizer interface on analytic objectives: a bounded
// quadratic (minimum inside and outside the box) and Rosenbrock's valley; budgets, evaluation
// caps and determinism.

#include <weft/optim/AdamOptimizer.h>
#include <weft/optim/LbfgsbOptimizer.h>

#include <gtest/gtest.h>

#include <limits>

namespace weft {
namespace {

// 0.5 (x - c)^T diag(w) (x - c): an anisotropic bowl centred at c.
class Quadratic : public Objective {
 public:
  Quadratic(Eigen::VectorXd centre, Eigen::VectorXd weights) : c_(std::move(centre)), w_(std::move(weights)) {}
  int dimension() const override { return static_cast<int>(c_.size()); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g = w_.cwiseProduct(x - c_);
    return 0.5 * (x - c_).dot(g);
  }
  long long stepsPerEvaluation() const override { return 10; }  // to exercise the budget

 private:
  Eigen::VectorXd c_, w_;
};

// (1 - x)^2 + 100 (y - x^2)^2, minimum 0 at (1, 1).
class Rosenbrock : public Objective {
 public:
  int dimension() const override { return 2; }
  double evaluate(const Eigen::VectorXd& p, Eigen::VectorXd& g) override {
    const double x = p[0], y = p[1];
    g.resize(2);
    g[0] = -2.0 * (1.0 - x) - 400.0 * x * (y - x * x);
    g[1] = 200.0 * (y - x * x);
    return (1.0 - x) * (1.0 - x) + 100.0 * (y - x * x) * (y - x * x);
  }
};

const double kInf = std::numeric_limits<double>::infinity();

std::unique_ptr<Optimizer> make(const std::string& method, OptimizerSettings s) {
  auto o = makeOptimizer(method, s);
  EXPECT_TRUE(o) << method;
  return o;
}

OptimizerSettings adamSettings() {
  OptimizerSettings s;
  s.learningRate = 0.02;
  s.maxEvaluations = 20000;
  s.gradientTolerance = 1e-7;
  return s;
}

TEST(AnalyticOptimizer, LbfgsbFindsTheQuadraticMinimumInsideTheBox) {
  Quadratic f(Eigen::Vector3d(0.3, -1.2, 2.0), Eigen::Vector3d(1.0, 10.0, 100.0));
  auto o = make("lbfgsb", OptimizerSettings{});
  const auto r = o->minimize(f, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5));
  EXPECT_NEAR(r.x[0], 0.3, 1e-6);
  EXPECT_NEAR(r.x[1], -1.2, 1e-6);
  EXPECT_NEAR(r.x[2], 2.0, 1e-6);
  EXPECT_LT(r.loss, 1e-10);
  EXPECT_LT(r.evaluations, 50);
  EXPECT_EQ(r.steps, 10LL * r.evaluations);
  EXPECT_EQ(o->log().entries().size(), static_cast<std::size_t>(r.evaluations));
}

TEST(AnalyticOptimizer, AdamFindsTheQuadraticMinimumInsideTheBox) {
  Quadratic f(Eigen::Vector3d(0.3, -1.2, 2.0), Eigen::Vector3d(1.0, 10.0, 100.0));
  auto o = make("adam", adamSettings());
  const auto r = o->minimize(f, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5));
  EXPECT_NEAR(r.x[0], 0.3, 1e-4);
  EXPECT_NEAR(r.x[1], -1.2, 1e-4);
  EXPECT_NEAR(r.x[2], 2.0, 1e-4);
}

TEST(AnalyticOptimizer, MinimumOutsideTheBoxLandsOnTheBound) {
  // The unconstrained minimum (3, -2) lies outside [-1, 1]^2: the constrained one is the corner
  // (1, -1), and no evaluated point may leave the box.
  for (const std::string method : {"lbfgsb", "adam"}) {
    SCOPED_TRACE(method);
    Quadratic f(Eigen::Vector2d(3.0, -2.0), Eigen::Vector2d(1.0, 4.0));
    auto o = make(method, method == "adam" ? adamSettings() : OptimizerSettings{});
    const Eigen::Vector2d lower(-1, -1), upper(1, 1);
    const auto r = o->minimize(f, Eigen::Vector2d(0.2, 0.5), lower, upper);
    EXPECT_NEAR(r.x[0], 1.0, 1e-9);
    EXPECT_NEAR(r.x[1], -1.0, 1e-9);
    for (const LogEntry& e : o->log().entries()) {
      EXPECT_TRUE((e.x.array() >= lower.array()).all() && (e.x.array() <= upper.array()).all()) << e.x.transpose();
    }
    EXPECT_LT(r.projectedGradientNorm, 1e-6);
  }
}

TEST(AnalyticOptimizer, LbfgsbSolvesRosenbrock) {
  Rosenbrock f;
  OptimizerSettings s;
  s.gradientTolerance = 1e-9;
  auto o = make("lbfgsb", s);
  const auto r = o->minimize(f, Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(kInf, kInf));
  EXPECT_NEAR(r.x[0], 1.0, 1e-5) << r.stopReason;
  EXPECT_NEAR(r.x[1], 1.0, 1e-5) << r.stopReason;
  EXPECT_LT(r.evaluations, 200);
}

TEST(AnalyticOptimizer, AdamSolvesRosenbrock) {
  Rosenbrock f;
  OptimizerSettings s = adamSettings();
  s.learningRate = 0.01;
  s.maxEvaluations = 50000;
  auto o = make("adam", s);
  const auto r = o->minimize(f, Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
  EXPECT_NEAR(r.x[0], 1.0, 1e-3) << r.stopReason;
  EXPECT_NEAR(r.x[1], 1.0, 2e-3) << r.stopReason;
}

TEST(AnalyticOptimizer, BoundedRosenbrockStopsOnTheBound) {
  // With x <= 0.5 the constrained minimum is at x = 0.5, y = 0.25.
  for (const std::string method : {"lbfgsb", "adam"}) {
    SCOPED_TRACE(method);
    Rosenbrock f;
    OptimizerSettings s = method == "adam" ? adamSettings() : OptimizerSettings{};
    if (method == "adam") s.maxEvaluations = 50000, s.learningRate = 0.01;
    auto o = make(method, s);
    const auto r = o->minimize(f, Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(-2, -2), Eigen::Vector2d(0.5, 2));
    EXPECT_NEAR(r.x[0], 0.5, 1e-6);
    EXPECT_NEAR(r.x[1], 0.25, 1e-3);
  }
}

TEST(AnalyticOptimizer, BudgetAndEvaluationCapStopBeforeExceeding) {
  for (const std::string method : {"lbfgsb", "adam"}) {
    SCOPED_TRACE(method);
    Rosenbrock r0;
    Quadratic f(Eigen::Vector2d(3.0, -2.0), Eigen::Vector2d(1.0, 1000.0));
    OptimizerSettings s;
    s.budget = 75;  // 7 evaluations of 10 steps fit, the 8th would not
    s.gradientTolerance = 0.0;
    auto o = make(method, s);
    const auto r = o->minimize(f, Eigen::Vector2d(0, 0), Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(kInf, kInf));
    EXPECT_EQ(r.stopReason, "budget");
    EXPECT_EQ(r.evaluations, 7);
    EXPECT_EQ(r.steps, 70);
    OptimizerSettings capped;
    capped.maxEvaluations = 5;
    capped.gradientTolerance = 0.0;
    auto o2 = make(method, capped);
    const auto r2 = o2->minimize(r0, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(kInf, kInf));
    EXPECT_EQ(r2.stopReason, "max evaluations");
    EXPECT_EQ(r2.evaluations, 5);
    // The result is the best point logged, not the last one tried.
    for (const LogEntry& e : o2->log().entries()) EXPECT_GE(e.loss, r2.loss);
  }
}

TEST(AnalyticOptimizer, SameSeedSameResult) {
  for (const std::string method : {"lbfgsb", "adam"}) {
    SCOPED_TRACE(method);
    OptimizerSettings s = method == "adam" ? adamSettings() : OptimizerSettings{};
    s.seed = 7;
    s.maxEvaluations = 300;
    Rosenbrock f1, f2;
    auto a = make(method, s), b = make(method, s);
    const auto ra = a->minimize(f1, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    const auto rb = b->minimize(f2, Eigen::Vector2d(-1.2, 1), Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
    ASSERT_EQ(a->log().entries().size(), b->log().entries().size());
    for (std::size_t i = 0; i < a->log().entries().size(); ++i) {
      EXPECT_EQ(a->log().entries()[i].loss, b->log().entries()[i].loss);
      EXPECT_EQ(a->log().entries()[i].x, b->log().entries()[i].x);
    }
    EXPECT_EQ(ra.x, rb.x);
    EXPECT_EQ(ra.stopReason, rb.stopReason);
  }
}

}  // namespace
}  // namespace weft
