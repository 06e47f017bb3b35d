#pragma once
// The interface both gradient-based methods share (L-BFGS-B, Adam): minimise an Objective inside a
// box, stopping on convergence, on the evaluation cap, or before an evaluation would exceed the
// budget of simulated steps (DiffCloth's tables count cost in simulated steps, forward and
// backward). Every evaluation goes through evaluate(), which enforces the budget and logs; the
// result is the best point logged.

#include <weft/optim/Objective.h>
#include <weft/optim/OptimizationLog.h>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace weft {

struct OptimizerSettings {
  long long budget = 0;            // simulated steps, forward + backward; 0 = unlimited
  int maxEvaluations = 0;          // 0 = unlimited
  int maxIterations = 0;           // 0 = unlimited
  double gradientTolerance = 1e-8; // projected gradient, infinity norm, optimiser coordinates
  double lossTolerance = 1e-12;    // relative loss change between iterations
  unsigned seed = 0;
  double learningRate = 0.05;      // Adam's step in optimiser coordinates
};

struct OptimizationResult {
  Eigen::VectorXd x;         // best point evaluated, optimiser coordinates
  double loss = 0.0;
  Eigen::VectorXd gradient;  // at x
  double projectedGradientNorm = 0.0;  // infinity norm of the bound-projected gradient at x
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

  // x0 is projected into [lower, upper] first. Throws what the objective throws (InputError,
  // NumericalError); running out of budget or evaluations is a normal stop.
  OptimizationResult minimize(Objective& objective, const Eigen::VectorXd& x0, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper);
  OptimizationLog& log() { return log_; }
  const OptimizationLog& log() const { return log_; }
  const OptimizerSettings& settings() const { return settings_; }

 protected:
  // The method itself: returns the stop reason. Iterations are counted in iterations_.
  virtual std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) = 0;
  // One logged, budgeted evaluation. Throws StopRequest when the budget or the evaluation cap
  // would be exceeded; minimize() catches it.
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient);
  int iterations_ = 0;

 private:
  OptimizerSettings settings_;
  Objective* objective_ = nullptr;
  OptimizationLog log_;
};

// Infinity norm of the gradient projected onto the box: components pushing outward at an active
// bound do not count (the first-order optimality measure of bound-constrained problems).
double projectedGradientNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient, const Eigen::VectorXd& lower,
                             const Eigen::VectorXd& upper);

// "lbfgsb" or "adam"; nullptr for an unknown name.
std::unique_ptr<Optimizer> makeOptimizer(const std::string& method, const OptimizerSettings& settings);

}  // namespace weft
