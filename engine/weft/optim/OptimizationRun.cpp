#include <weft/optim/OptimizationRun.h>

#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/optim/SmoothedObjective.h>

namespace weft {
namespace {

const std::string& knownMethod(const Scene& scene, const std::string& method) {
  if (!makeOptimizer(method, OptimizerSettings{}))
    throw InputError(scene.file, "method",
                     "unknown optimisation method '" + method + "' (lbfgsb, adam, cmaes, es1p1)");
  return method;
}

ParameterSet chosenParameters(const Scene& scene, const std::vector<std::string>& paths) {
  if (!scene.task) throw InputError(scene.file, "task", "the scene has no task to optimise");
  const ParameterSet parameters =
      paths.empty() ? ParameterSet::fromTask(scene) : ParameterSet::fromPaths(scene, paths);
  if (parameters.empty())
    throw InputError(scene.file, "task.parameters", "no parameters to optimise");
  return parameters;
}

// The objective as the optimiser sees it: the caller's hook before every evaluation (a pause, a
// cancellation), then the simulation.
class HookedObjective final : public Objective {
 public:
  HookedObjective(Objective& inner, const std::function<void()>& before)
      : inner_(inner), before_(before) {}
  int dimension() const override { return inner_.dimension(); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) override {
    if (before_) before_();
    return inner_.evaluate(x, gradient);
  }
  double value(const Eigen::VectorXd& x) override {
    if (before_) before_();
    return inner_.value(x);
  }
  long long stepsPerEvaluation() const override { return inner_.stepsPerEvaluation(); }
  long long stepsPerValue() const override { return inner_.stepsPerValue(); }
  double lastGradientError() const override { return inner_.lastGradientError(); }

 private:
  Objective& inner_;
  const std::function<void()>& before_;
};

}  // namespace

OptimizationRun::OptimizationRun(const Scene& scene, const std::string& method,
                                 const std::vector<std::string>& parameters)
    : method_(knownMethod(scene, method)),
      usesGradient_(makeOptimizer(method, OptimizerSettings{})->usesGradient()),
      objective_(scene, chosenParameters(scene, parameters)) {}

OptimizationRun::~OptimizationRun() = default;

OptimizationOutcome OptimizationRun::run(const OptimizerSettings& settings,
                                         const OptimizationCallbacks& callbacks) {
  return run(settings, space().toCoordinates(space().initialValues()), callbacks);
}

OptimizationOutcome OptimizationRun::run(const OptimizerSettings& settings,
                                         const Eigen::VectorXd& start,
                                         const OptimizationCallbacks& callbacks) {
  optimizer_ = makeOptimizer(method_, settings);
  if (callbacks.evaluated)
    optimizer_->log().setObserver([this, evaluated = callbacks.evaluated](const LogEntry& e) {
      evaluated(e, space().toValues(e.x));
    });
  HookedObjective objective(objective_, callbacks.beforeEvaluation);
  OptimizationOutcome outcome;
  if (settings.smoothingSigma > 0.0) {
    if (!usesGradient_)
      throw InputError(objective_.scene().file, "smoothing",
                       "smoothing is for the gradient-based methods (lbfgsb, adam); '" + method_ +
                           "' does not use gradients");
    SmoothedObjective smoothed(objective, settings.smoothingSigma, settings.smoothingPairs,
                               settings.seed, space().lowerCoordinates(),
                               space().upperCoordinates());
    outcome.result = optimizer_->minimize(smoothed, start, space().lowerCoordinates(),
                                          space().upperCoordinates());
    outcome.lastGradientVariance = smoothed.lastGradientVariance();
    if (!optimizer_->log().empty()) outcome.unsmoothedLoss = objective_.value(outcome.result.x);
  } else {
    outcome.result = optimizer_->minimize(objective, start, space().lowerCoordinates(),
                                          space().upperCoordinates());
  }
  outcome.bestValues = space().toValues(outcome.result.x);
  return outcome;
}

const OptimizationLog& OptimizationRun::log() const {
  static const OptimizationLog none;
  return optimizer_ ? optimizer_->log() : none;
}

}  // namespace weft
