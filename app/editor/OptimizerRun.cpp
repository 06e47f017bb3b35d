#include "OptimizerRun.h"

#include "WorkerThreads.h"

#include <weft/core/Error.h>

#include <cmath>

namespace weft::editor {

std::vector<std::string> OptimizerRun::methods() {
  // Every name the command line documents, in its order; makeOptimizer decides which exist
  // (asked once: the answer is fixed for the binary, and the panel asks every frame).
  static const std::vector<std::string> names = [] {
    std::vector<std::string> found;
    for (const char* name : {"lbfgsb", "adam", "cmaes", "es1p1"})
      if (makeOptimizer(name, OptimizerSettings{})) found.emplace_back(name);
    return found;
  }();
  return names;
}

OptimizerRun::OptimizerRun() = default;

OptimizerRun::~OptimizerRun() {
  if (gate_) gate_->cancel();
  join();
}

void OptimizerRun::join() {
  if (worker_.joinable()) worker_.join();
}

std::string OptimizerRun::start(const Scene& scene, const Setup& setup, bool paused) {
  cancel();
  if (!makeOptimizer(setup.method, setup.settings))
    return "unknown optimisation method '" + setup.method + "'";
  if (setup.parameters.empty()) return "choose at least one parameter to optimise";
  std::unique_ptr<OptimizationRun> run;
  try {
    if (!scene.task)
      throw InputError(scene.file, "task",
                       "the scene has no task: set targets or load a target motion first");
    run = std::make_unique<OptimizationRun>(scene, setup.method, setup.parameters);
  } catch (const std::exception& e) {
    return e.what();
  }

  const ParameterSpace& space = run->space();
  method_ = setup.method;
  parameters_ = setup.parameters;
  const Eigen::VectorXd lower = space.lowerValues(), upper = space.upperValues(),
                        initial = space.initialValues();
  lower_.assign(lower.data(), lower.data() + lower.size());
  upper_.assign(upper.data(), upper.data() + upper.size());
  initial_.assign(initial.data(), initial.data() + initial.size());
  startDocument_ = scene.document;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    samples_.clear();
    unconverged_ = 0;
    progress_ = Progress();
    missingAccuracy_ = 0;
    largestError_ = 0.0;
    error_.clear();
    stopReason_.clear();
  }
  gate_ = std::make_unique<EvaluationGate>();
  if (paused) gate_->pause();
  run_ = std::move(run);
  settings_ = setup.settings;
  status_ = Status::Running;
  worker_ = std::thread([this] {
    useWorkerThreads();
    OptimizationCallbacks callbacks;
    callbacks.beforeEvaluation = [this] { gate_->enter(); };
    callbacks.stepDone = [this](PassPhase phase, int pass, int done, int total) {
      gate_->check();  // a cancel ends the evaluation here, within a step
      std::lock_guard<std::mutex> lock(mutex_);
      progress_ = {true, static_cast<int>(samples_.size()) + 1, phase, pass, done, total};
    };
    callbacks.evaluated = [this](const LogEntry& e, const Eigen::VectorXd& v) {
      Sample s;
      s.evaluation = e.evaluation;
      s.steps = e.steps;
      s.loss = e.loss;
      s.values.assign(v.data(), v.data() + v.size());
      s.hasGradient = e.hasGradient;
      s.gradientError = e.gradientError;
      // (The objective is the worker's: read here, on the worker, after its evaluation.)
      const SimulationObjective& objective = run_->objective();
      const int unconverged = objective.unconvergedForwardSteps();
      const int missing = objective.gradientsMissingAccuracy();
      const double largest = objective.largestGradientError();
      std::lock_guard<std::mutex> lock(mutex_);
      s.unconvergedSteps = unconverged - unconverged_;
      samples_.push_back(std::move(s));
      progress_.active = false;
      unconverged_ = unconverged;
      missingAccuracy_ = missing;
      largestError_ = largest;
    };
    try {
      const OptimizationOutcome outcome = run_->run(settings_, callbacks);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        stopReason_ = outcome.result.stopReason;
        progress_.active = false;
      }
      status_ = Status::Finished;
    } catch (const EvaluationCancelled&) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        stopReason_ = "cancelled";
        progress_.active = false;
      }
      status_ = Status::Cancelled;
    } catch (const std::exception& e) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = e.what();
        progress_.active = false;
      }
      status_ = Status::Failed;
    }
  });
  return "";
}

void OptimizerRun::pause() {
  if (gate_) gate_->pause();
}

void OptimizerRun::resume() {
  if (gate_) gate_->resume();
}

void OptimizerRun::step(int evaluations) {
  if (gate_) gate_->allow(evaluations);
}

void OptimizerRun::cancel() {
  if (gate_) gate_->cancel();
  join();
}

void OptimizerRun::wait() {
  join();
}

OptimizerRun::Status OptimizerRun::status() const {
  const Status s = status_.load();
  if (s == Status::Running && gate_ && gate_->paused() && gate_->waiting()) return Status::Paused;
  return s;
}

const char* OptimizerRun::statusName(Status status) {
  switch (status) {
    case Status::Idle:
      return "idle";
    case Status::Running:
      return "running";
    case Status::Paused:
      return "paused";
    case Status::Finished:
      return "finished";
    case Status::Cancelled:
      return "cancelled";
    case Status::Failed:
      return "failed";
  }
  return "?";
}

std::string OptimizerRun::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

std::string OptimizerRun::stopReason() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stopReason_;
}

int OptimizerRun::gradientsMissingAccuracy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return missingAccuracy_;
}

double OptimizerRun::largestGradientError() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return largestError_;
}

int OptimizerRun::unconvergedForwardSteps() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return unconverged_;
}

OptimizerRun::Progress OptimizerRun::progress() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return progress_;
}

std::vector<OptimizerRun::Sample> OptimizerRun::samples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return samples_;
}

int OptimizerRun::evaluations() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(samples_.size());
}

std::optional<OptimizerRun::Sample> OptimizerRun::best() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<Sample> best;
  for (const Sample& s : samples_)
    if (std::isfinite(s.loss) && (!best || s.loss < best->loss)) best = s;
  return best;
}

}  // namespace weft::editor
