// Evaluations asked for together (Optimizer::evaluateValues: CMA-ES's population, the
// (1+1)-ES's speculative offspring) give the run one at a time would have given, entry for
// entry, whatever the objective's concurrency: what lets `weft optimize --method cmaes|es1p1`
// under mpirun write the serial run's loss.csv. The objective here evaluates a batch "at once"
// by computing its points in reverse order, as another process might finish them.

#include "AnalyticObjectives.h"

#include <weft/optim/Optimizer.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace weft {
namespace {

// A rotated, shifted quadratic with a plateau (equal losses, which the (1+1)-ES accepts) and,
// optionally, a point that throws; evaluates a batch of up to `concurrency` points together.
class BatchObjective : public Objective {
 public:
  BatchObjective(int concurrency, double failAbove)
      : concurrency_(concurrency), failAbove_(failAbove) {}
  int dimension() const override { return 3; }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g = Eigen::VectorXd::Zero(3);
    return value(x);
  }
  double value(const Eigen::VectorXd& x) override {
    ++evaluated;
    if (x[1] > failAbove_) throw std::runtime_error("point outside the model");
    const double r = (x - Eigen::Vector3d(0.3, -0.2, 0.1)).squaredNorm();
    return r < 0.01 ? 0.01 : r + 0.1 * x[0] * x[1];  // flat near the minimum
  }
  void values(const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses) override {
    if (concurrency_ == 1) return Objective::values(points, losses);
    ++batches;
    largestBatch = std::max(largestBatch, static_cast<int>(points.size()));
    std::vector<double> computed(points.size());
    std::string failure;
    std::size_t failedAt = points.size();
    for (std::size_t k = points.size(); k-- > 0;) {
      try {
        computed[k] = value(points[k]);
      } catch (const std::runtime_error& e) {
        failedAt = k, failure = e.what();
      }
    }
    for (std::size_t k = 0; k < failedAt; ++k) losses.push_back(computed[k]);
    if (failedAt < points.size()) throw std::runtime_error(failure);
  }
  int concurrency() const override { return concurrency_; }
  long long stepsPerValue() const override { return 7; }
  long long stepsPerEvaluation() const override { return 14; }

  int evaluated = 0, batches = 0, largestBatch = 0;

 private:
  int concurrency_;
  double failAbove_;
};

struct LoggedRun {
  std::vector<double> losses;
  std::vector<Eigen::VectorXd> points;
  std::vector<long long> steps;
  std::string stop;
  std::string error;
  int iterations = 0;
};

LoggedRun runMethod(const std::string& method, int concurrency, const OptimizerSettings& settings,
                    double failAbove = 1e9) {
  BatchObjective objective(concurrency, failAbove);
  auto optimizer = makeOptimizer(method, settings);
  LoggedRun run;
  try {
    const OptimizationResult r =
        optimizer->minimize(objective, Eigen::Vector3d(0.8, 0.7, -0.6),
                            Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1.5));
    run.stop = r.stopReason;
    run.iterations = r.iterations;
  } catch (const std::runtime_error& e) {
    run.error = e.what();
  }
  for (const LogEntry& e : optimizer->log().entries()) {
    run.losses.push_back(e.loss);
    run.points.push_back(e.x);
    run.steps.push_back(e.steps);
  }
  if (concurrency > 1) {
    EXPECT_GT(objective.batches, 0) << method << ": the batch path was never taken";
    if (method == "es1p1") {
      EXPECT_EQ(objective.largestBatch, concurrency) << "speculation never filled a batch";
      EXPECT_GE(objective.evaluated, static_cast<int>(run.losses.size()));
    }
  }
  return run;
}

void expectSameRun(const LoggedRun& serial, const LoggedRun& batched, const std::string& what) {
  ASSERT_EQ(serial.losses.size(), batched.losses.size()) << what;
  for (std::size_t k = 0; k < serial.losses.size(); ++k) {
    EXPECT_EQ(serial.losses[k], batched.losses[k]) << what << ", entry " << k;
    EXPECT_EQ(serial.points[k], batched.points[k]) << what << ", entry " << k;
    EXPECT_EQ(serial.steps[k], batched.steps[k]) << what << ", entry " << k;
  }
  EXPECT_EQ(serial.stop, batched.stop) << what;
  EXPECT_EQ(serial.error, batched.error) << what;
  EXPECT_EQ(serial.iterations, batched.iterations) << what;
}

class PopulationEvaluation : public ::testing::TestWithParam<std::string> {};

TEST_P(PopulationEvaluation, BatchesGiveTheOneAtATimeRunUnderEveryStop) {
  const std::string method = GetParam();
  struct Case {
    const char* name;
    long long budget;
    int maxEvaluations, maxIterations;
  };
  // Budgets and caps that end the run in the middle of a batch (7 steps per value).
  const Case cases[] = {{"budget", 7 * 61, 0, 0},
                        {"evaluations", 0, 47, 0},
                        {"iterations", 0, 0, 13},
                        {"long", 7 * 400, 0, 0}};
  for (const Case& c : cases) {
    OptimizerSettings settings;
    settings.budget = c.budget;
    settings.maxEvaluations = c.maxEvaluations;
    settings.maxIterations = c.maxIterations;
    settings.seed = 11;
    const LoggedRun serial = runMethod(method, 1, settings);
    ASSERT_GT(serial.losses.size(), 10u) << c.name;
    for (int concurrency : {2, 3, 5}) {
      const LoggedRun batched = runMethod(method, concurrency, settings);
      expectSameRun(serial, batched,
                    method + " " + c.name + ", concurrency " + std::to_string(concurrency));
    }
  }
}

TEST_P(PopulationEvaluation, AFailingPointEndsTheRunAfterTheSameEntries) {
  const std::string method = GetParam();
  OptimizerSettings settings;
  settings.budget = 7 * 400;
  settings.seed = 5;
  // Points with x1 > 0.75 fail: the start (0.7) does not, early samples do.
  const LoggedRun serial = runMethod(method, 1, settings, 0.75);
  ASSERT_EQ(serial.error, "point outside the model") << "the case must reach a failing point";
  for (int concurrency : {2, 4}) {
    const LoggedRun batched = runMethod(method, concurrency, settings, 0.75);
    expectSameRun(serial, batched, method + ", concurrency " + std::to_string(concurrency));
  }
}

INSTANTIATE_TEST_SUITE_P(GradientFree, PopulationEvaluation, ::testing::Values("cmaes", "es1p1"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace weft
