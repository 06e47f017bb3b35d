#include <weft/optim/OptimizationRun.h>

#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/optim/SmoothedObjective.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

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
// cancellation), then the simulation; with workers, points asked for together are simulated
// on all their processes at once.
class HookedObjective final : public Objective {
 public:
  HookedObjective(SimulationObjective& inner, const std::function<void()>& before,
                  WorkDistributor* workers)
      : inner_(inner), before_(before), workers_(workers) {}
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
  int concurrency() const override { return workers_ ? workers_->size() : 1; }
  void values(const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses) override {
    if (!workers_ || workers_->size() == 1) return Objective::values(points, losses);
    for (std::size_t k = 0; k < points.size(); ++k)
      if (before_) before_();
    // Each item: the loss, the forward steps that stopped above tolerance, the seconds.
    struct Tally {
      double loss;
      int unconverged;
      double seconds;
    };
    const std::vector<WorkItemResult> results = workers_->map(points.size(), [&](std::size_t k) {
      const int before = inner_.unconvergedForwardSteps();
      const double secondsBefore = inner_.forwardSeconds();
      Tally t{};
      t.loss = inner_.value(points[k]);
      t.unconverged = inner_.unconvergedForwardSteps() - before;
      t.seconds = inner_.forwardSeconds() - secondsBefore;
      return std::string(reinterpret_cast<const char*>(&t), sizeof t);
    });
    for (const WorkItemResult& r : results) {
      if (!r.ok) rethrowFailure(r);  // with the losses before it appended, as one at a time
      Tally t{};
      if (r.data.size() != sizeof t) throw std::runtime_error("a population item's result is torn");
      std::memcpy(&t, r.data.data(), sizeof t);
      if (r.rank != workers_->rank()) inner_.countValueRunElsewhere(t.unconverged, t.seconds);
      losses.push_back(t.loss);
    }
  }

 private:
  SimulationObjective& inner_;
  const std::function<void()>& before_;
  WorkDistributor* workers_;
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
  // Heard for this run only: the callbacks may not outlive it.
  struct ProgressScope {
    SimulationObjective& objective;
    ~ProgressScope() { objective.setProgress({}); }
  } progressScope{objective_};
  objective_.setProgress(callbacks.stepDone);
  if (callbacks.evaluated)
    optimizer_->log().setObserver([this, evaluated = callbacks.evaluated](const LogEntry& e) {
      evaluated(e, space().toValues(e.x));
    });
  HookedObjective objective(objective_, callbacks.beforeEvaluation, workers_);
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
