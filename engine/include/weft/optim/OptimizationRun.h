#pragma once
// One optimisation of a scene's task: the chosen parameters (the task's task.parameters, or the
// paths given) as a ParameterSpace, the SimulationObjective over them (forward pass + adjoint, or
// the forward pass alone for the gradient-free methods), the method makeOptimizer names, run
// from the scene's own values (or a given start) within the space's bounds. The one assembly
// `weft optimize`, the editor's optimiser panel and `weft bench applications` share; what each
// does with the evaluations (loss.csv, a live curve, a run store) is its own, through the
// callbacks.

#include <weft/distributed/WorkDistributor.h>
#include <weft/optim/OptimizationLog.h>
#include <weft/optim/Optimizer.h>
#include <weft/optim/SimulationObjective.h>

#include <Eigen/Core>

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace weft {

struct OptimizationCallbacks {
  // After every evaluation: the log entry and its parameter values (physical units, in the order
  // of the space's parameters). May throw to end the run (the exception leaves run()).
  std::function<void(const LogEntry&, const Eigen::VectorXd& values)> evaluated;
  // Before every evaluation: may block (a paused run) or throw to cancel (the exception leaves
  // run(); the evaluations so far stay in log()).
  std::function<void()> beforeEvaluation;
  // After every forward and backward step inside an evaluation (SimulationObjective::setProgress):
  // may throw to cancel within the evaluation. Evaluations other processes run are not heard.
  StepProgress stepDone;
};

struct OptimizationOutcome {
  OptimizationResult result;   // the best point (optimiser coordinates), evaluations, stop reason
  Eigen::VectorXd bestValues;  // result.x in physical units
  // With smoothing (settings.smoothingSigma > 0) the log's losses are smoothed ones; this is the
  // task loss itself at result.x, from one more forward run outside the budget (NaN without
  // smoothing). Also the last gradient's sampling variance (SmoothedObjective).
  double unsmoothedLoss = std::numeric_limits<double>::quiet_NaN();
  double lastGradientVariance = 0.0;
};

class OptimizationRun {
 public:
  // `scene` must be validated and have a task. `parameters`: JSON paths, empty for the task's.
  // Throws InputError for an unknown method, no parameters, paths that cannot be resolved or
  // bounded, or unreadable loss targets (SimulationObjective).
  OptimizationRun(const Scene& scene, const std::string& method,
                  const std::vector<std::string>& parameters = {});
  ~OptimizationRun();
  OptimizationRun(const OptimizationRun&) = delete;
  OptimizationRun& operator=(const OptimizationRun&) = delete;

  const std::string& method() const { return method_; }
  // Whether the method asks for gradients: one evaluation costs 2 x time.steps, else time.steps.
  bool usesGradient() const { return usesGradient_; }
  long long stepsPerEvaluation() const {
    return usesGradient_ ? objective_.stepsPerEvaluation() : objective_.stepsPerValue();
  }
  // The same with the settings' smoothing: 2 x smoothingPairs times that.
  long long stepsPerEvaluation(const OptimizerSettings& settings) const {
    return settings.smoothingSigma > 0.0 ? 2LL * settings.smoothingPairs * stepsPerEvaluation()
                                         : stepsPerEvaluation();
  }
  const ParameterSpace& space() const { return objective_.space(); }
  const SimulationObjective& objective() const { return objective_; }

  // Minimises from the scene's values. Smoothing (settings.smoothingSigma > 0) needs a
  // gradient-based method (InputError otherwise). Throws what the objective or the callbacks throw
  // (InputError, NumericalError, a cancellation); running out of budget is a normal stop.
  OptimizationOutcome run(const OptimizerSettings& settings,
                          const OptimizationCallbacks& callbacks = {});
  // The same from `start`, optimiser coordinates (projected into the box first).
  OptimizationOutcome run(const OptimizerSettings& settings, const Eigen::VectorXd& start,
                          const OptimizationCallbacks& callbacks = {});
  // Every evaluation of the last run (empty before one).
  const OptimizationLog& log() const;
  // Spreads the evaluations the method asks for at once (CMA-ES's population, the (1+1)-ES's
  // speculative offspring) over `workers`' processes; every rank runs the same optimisation and
  // gets the same log. nullptr (the default): one process. Gradient evaluations stay local.
  void setWorkers(WorkDistributor* workers) { workers_ = workers; }

 private:
  std::string method_;
  bool usesGradient_ = true;
  SimulationObjective objective_;
  std::unique_ptr<Optimizer> optimizer_;
  WorkDistributor* workers_ = nullptr;
};

}  // namespace weft
