#pragma once
// The interface every method shares, gradient-based (L-BFGS-B, Adam) and gradient-free (CMA-ES,
// (1+1)-ES): minimise an Objective inside a box, stopping on convergence, on the evaluation cap,
// or before an evaluation would exceed the budget of simulated steps (DiffCloth's tables count
// cost in simulated steps: a forward step 1, a backward step 1 more). Every evaluation goes
// through evaluate() (value and gradient, Objective::stepsPerEvaluation) or evaluateValue()
// (value alone, Objective::stepsPerValue), which enforce the budget and log; the result is the
// best point logged.

#include <weft/optim/Objective.h>
#include <weft/optim/OptimizationLog.h>

#include <Eigen/Core>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace weft {

struct OptimizerSettings {
  long long budget = 0;             // simulated steps, forward + backward; 0 = unlimited
  int maxEvaluations = 0;           // 0 = unlimited
  int maxIterations = 0;            // 0 = unlimited
  double gradientTolerance = 1e-8;  // projected gradient, infinity norm, optimiser coordinates
  double lossTolerance = 1e-12;     // relative loss change between iterations
  unsigned seed = 0;                // the evolution strategies' random stream (std::mt19937_64)
  double learningRate = 0.05;       // Adam's step in optimiser coordinates
  // L-BFGS-B (LbfgsbOptimizer.h): the first trial step's length in optimiser coordinates (1 is
  // LBFGSpp's), and the shortest step whose curvature pair enters the BFGS matrix (0: all).
  double lbfgsbFirstStep = 1.0;
  double lbfgsbMinCurvatureStep = 0.0;
  // Gaussian smoothing of the objective for gradient-based methods (optim/SmoothedObjective.h):
  // the standard deviation in optimiser coordinates (0: off) and the antithetic pairs per
  // evaluation; the directions come from `seed`.
  double smoothingSigma = 0.0;
  int smoothingPairs = 4;
};

struct OptimizationResult {
  Eigen::VectorXd x;  // best point evaluated, optimiser coordinates
  double loss = 0.0;
  bool hasGradient = false;    // whether x was a gradient evaluation (never for CMA-ES, (1+1)-ES)
  Eigen::VectorXd gradient;    // at x, when hasGradient (else empty)
  double gradientError = 0.0;  // its estimated relative error (Objective::lastGradientError)
  double projectedGradientNorm =
      0.0;  // infinity norm of the bound-projected gradient at x (NaN without one)
  int evaluations = 0;
  int iterations = 0;
  long long steps = 0;
  std::string stopReason;
};

class Optimizer {
 public:
  explicit Optimizer(OptimizerSettings settings) : settings_(settings) {}
  virtual ~Optimizer() = default;
  virtual std::string name() const = 0;
  // Whether the method asks for gradients (evaluate) or values alone (evaluateValue): what one of
  // its evaluations of a simulation costs, 2 * steps or steps.
  virtual bool usesGradient() const { return true; }

  // x0 is projected into [lower, upper] first. Throws what the objective throws (InputError,
  // NumericalError); running out of budget or evaluations is a normal stop.
  OptimizationResult minimize(Objective& objective, const Eigen::VectorXd& x0,
                              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);
  OptimizationLog& log() { return log_; }
  const OptimizationLog& log() const { return log_; }
  const OptimizerSettings& settings() const { return settings_; }

 protected:
  // The method itself: returns the stop reason. Iterations are counted in iterations_.
  virtual std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                          const Eigen::VectorXd& upper) = 0;
  // One logged, budgeted evaluation with the gradient (costs stepsPerEvaluation). Throws
  // StopRequest when the budget or the evaluation cap would be exceeded; minimize() catches it.
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient);
  // The same for the value alone (costs stepsPerValue): what gradient-free methods call.
  double evaluateValue(const Eigen::VectorXd& x);
  // The values at several points at once (Objective::values, spread over processes when the
  // objective is), logged in order exactly as evaluateValue() one point at a time would have:
  // the points the cap and the budget admit are evaluated, and StopRequest follows their
  // entries. With `keepGoing`, the entries stop after the first loss it rejects (that entry
  // included): the points after it were speculative, evaluated at once in case it was rejected,
  // and are neither logged nor counted. Returns the logged losses. An objective of concurrency 1
  // is evaluated and logged one point at a time.
  std::vector<double> evaluateValues(const std::vector<Eigen::VectorXd>& points,
                                     const std::function<bool(double)>& keepGoing = {});
  // Points Objective::values() evaluates at once (1 without distribution).
  int concurrency() const;
  int iterations_ = 0;

 private:
  // Checks the cap and the budget for an evaluation costing `cost` steps (throws StopRequest).
  void admit(long long cost) const;
  // Why an evaluation costing `cost` steps, `ahead` evaluations after the logged ones, would not
  // be admitted ("max evaluations", "budget"), or empty when it would.
  std::string refusal(long long cost, long long ahead) const;
  double record(LogEntry entry, long long cost);

  OptimizerSettings settings_;
  Objective* objective_ = nullptr;
  OptimizationLog log_;
  std::chrono::steady_clock::time_point start_;
};

// Infinity norm of the gradient projected onto the box: components pushing outward at an active
// bound do not count (the first-order optimality measure of bound-constrained problems).
double projectedGradientNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient,
                             const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

// "lbfgsb", "adam", "cmaes" or "es1p1"; nullptr for an unknown name.
std::unique_ptr<Optimizer> makeOptimizer(const std::string& method,
                                         const OptimizerSettings& settings);

}  // namespace weft
