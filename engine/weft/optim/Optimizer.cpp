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

std::string Optimizer::refusal(long long cost, long long ahead) const {
  const long long done = static_cast<long long>(log_.entries().size()) + ahead;
  if (settings_.maxEvaluations > 0 && done >= settings_.maxEvaluations) return "max evaluations";
  if (settings_.budget > 0 && log_.steps() + cost * (ahead + 1) > settings_.budget) return "budget";
  return "";
}

void Optimizer::admit(long long cost) const {
  std::string reason = refusal(cost, 0);
  if (!reason.empty()) throw StopRequest{std::move(reason)};
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

std::vector<double> Optimizer::evaluateValues(const std::vector<Eigen::VectorXd>& points,
                                              const std::function<bool(double)>& keepGoing) {
  if (objective_->concurrency() <= 1) {
    // One at a time, each logged before the next starts: what a caller watching the log between
    // evaluations (the editor's step-by-step optimiser) relies on.
    std::vector<double> logged;
    for (const Eigen::VectorXd& x : points) {
      logged.push_back(evaluateValue(x));
      if (keepGoing && !keepGoing(logged.back())) break;
    }
    return logged;
  }
  const long long cost = objective_->stepsPerValue();
  // The prefix admit() lets through one point at a time, and why the next one is not.
  std::size_t admitted = 0;
  std::string stop;
  while (admitted < points.size() &&
         (stop = refusal(cost, static_cast<long long>(admitted))).empty())
    ++admitted;
  const std::vector<Eigen::VectorXd> batch(points.begin(),
                                           points.begin() + static_cast<std::ptrdiff_t>(admitted));
  std::vector<double> losses;
  losses.reserve(admitted);
  std::vector<double> logged;
  const auto recordUpTo = [&](std::size_t count) {
    for (std::size_t k = logged.size(); k < count; ++k) {
      LogEntry e;
      e.loss = losses[k];
      e.x = batch[k];
      logged.push_back(record(std::move(e), cost));
      if (keepGoing && !keepGoing(losses[k])) return false;
    }
    return true;
  };
  try {
    objective_->values(batch, losses);
  } catch (...) {
    // What evaluateValue() one at a time would have logged; and if a speculative point failed
    // after the one that ends the run of points, one at a time would never have evaluated it.
    if (!recordUpTo(losses.size())) return logged;
    throw;
  }
  if (!recordUpTo(losses.size())) return logged;
  if (admitted < points.size()) throw StopRequest{stop};
  return logged;
}

int Optimizer::concurrency() const {
  return objective_ ? objective_->concurrency() : 1;
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
