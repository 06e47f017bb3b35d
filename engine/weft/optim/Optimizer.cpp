#include <weft/optim/Optimizer.h>

#include <weft/optim/AdamOptimizer.h>
#include <weft/optim/CmaEsOptimizer.h>
#include <weft/optim/LbfgsbOptimizer.h>
#include <weft/optim/OnePlusOneEsOptimizer.h>

#include <limits>

namespace weft {
namespace {

// Thrown by evaluate() to unwind out of the method (LBFGSpp's minimize has no other way to be
// stopped from inside the objective).
struct StopRequest {
  std::string reason;
};

}  // namespace

double projectedGradientNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient,
                             const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  // The same measure as L-BFGS-B's: |P(x - g) - x|_inf with P the projection onto the box.
  return ((x - gradient).cwiseMax(lower).cwiseMin(upper) - x).cwiseAbs().maxCoeff();
}

void Optimizer::admit(long long cost) const {
  const int done = static_cast<int>(log_.entries().size());
  if (settings_.maxEvaluations > 0 && done >= settings_.maxEvaluations)
    throw StopRequest{"max evaluations"};
  if (settings_.budget > 0 && log_.steps() + cost > settings_.budget) throw StopRequest{"budget"};
}

double Optimizer::record(LogEntry e, long long cost) {
  e.evaluation = static_cast<int>(log_.entries().size()) + 1;
  e.steps = log_.steps() + cost;
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double loss = e.loss;
  log_.add(std::move(e));
  return loss;
}

double Optimizer::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  const long long cost = objective_->stepsPerEvaluation();
  admit(cost);
  LogEntry e;
  e.loss = objective_->evaluate(x, e.gradient);
  e.hasGradient = true;
  e.gradientError = objective_->lastGradientError();
  e.x = x;
  gradient = e.gradient;
  return record(std::move(e), cost);
}

double Optimizer::evaluateValue(const Eigen::VectorXd& x) {
  const long long cost = objective_->stepsPerValue();
  admit(cost);
  LogEntry e;
  e.loss = objective_->value(x);
  e.x = x;
  return record(std::move(e), cost);
}

OptimizationResult Optimizer::minimize(Objective& objective, const Eigen::VectorXd& x0,
                                       const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  objective_ = &objective;
  log_.clear();
  iterations_ = 0;
  start_ = std::chrono::steady_clock::now();
  OptimizationResult result;
  try {
    result.stopReason = run(x0.cwiseMax(lower).cwiseMin(upper), lower, upper);
  } catch (const StopRequest& stop) {
    result.stopReason = stop.reason;
  }
  objective_ = nullptr;
  if (!log_.empty()) {
    const LogEntry& best = log_.best();
    result.x = best.x;
    result.loss = best.loss;
    result.hasGradient = best.hasGradient;
    result.gradient = best.gradient;
    result.gradientError = best.gradientError;
    result.projectedGradientNorm = best.hasGradient
                                       ? projectedGradientNorm(best.x, best.gradient, lower, upper)
                                       : std::numeric_limits<double>::quiet_NaN();
  } else {
    result.x = x0.cwiseMax(lower).cwiseMin(upper);
  }
  result.evaluations = static_cast<int>(log_.entries().size());
  result.iterations = iterations_;
  result.steps = log_.steps();
  return result;
}

std::unique_ptr<Optimizer> makeOptimizer(const std::string& method,
                                         const OptimizerSettings& settings) {
  if (method == "lbfgsb") return std::make_unique<LbfgsbOptimizer>(settings);
  if (method == "adam") return std::make_unique<AdamOptimizer>(settings);
  if (method == "cmaes") return std::make_unique<CmaEsOptimizer>(settings);
  if (method == "es1p1") return std::make_unique<OnePlusOneEsOptimizer>(settings);
  return nullptr;
}

}  // namespace weft
