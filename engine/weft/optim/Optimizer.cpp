#include <weft/optim/Optimizer.h>

#include <weft/optim/AdamOptimizer.h>
#include <weft/optim/LbfgsbOptimizer.h>

namespace weft {
namespace {

// Thrown by evaluate() to unwind out of the method (LBFGSpp's minimize has no other way to be
// stopped from inside the objective).
struct StopRequest {
  std::string reason;
};

}  // namespace

double projectedGradientNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient, const Eigen::VectorXd& lower,
                             const Eigen::VectorXd& upper) {
  // The same measure as L-BFGS-B's: |P(x - g) - x|_inf with P the projection onto the box.
  return ((x - gradient).cwiseMax(lower).cwiseMin(upper) - x).cwiseAbs().maxCoeff();
}

double Optimizer::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  const int done = static_cast<int>(log_.entries().size());
  if (settings_.maxEvaluations > 0 && done >= settings_.maxEvaluations) throw StopRequest{"max evaluations"};
  const long long cost = objective_->stepsPerEvaluation();
  if (settings_.budget > 0 && log_.steps() + cost > settings_.budget) throw StopRequest{"budget"};
  LogEntry e;
  e.loss = objective_->evaluate(x, e.gradient);
  e.evaluation = done + 1;
  e.steps = log_.steps() + cost;
  e.x = x;
  gradient = e.gradient;
  const double loss = e.loss;
  log_.add(std::move(e));
  return loss;
}

OptimizationResult Optimizer::minimize(Objective& objective, const Eigen::VectorXd& x0, const Eigen::VectorXd& lower,
                                       const Eigen::VectorXd& upper) {
  objective_ = &objective;
  log_.clear();
  iterations_ = 0;
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
    result.gradient = best.gradient;
    result.projectedGradientNorm = projectedGradientNorm(best.x, best.gradient, lower, upper);
  } else {
    result.x = x0.cwiseMax(lower).cwiseMin(upper);
  }
  result.evaluations = static_cast<int>(log_.entries().size());
  result.iterations = iterations_;
  result.steps = log_.steps();
  return result;
}

std::unique_ptr<Optimizer> makeOptimizer(const std::string& method, const OptimizerSettings& settings) {
  if (method == "lbfgsb") return std::make_unique<LbfgsbOptimizer>(settings);
  if (method == "adam") return std::make_unique<AdamOptimizer>(settings);
  return nullptr;
}

}  // namespace weft
