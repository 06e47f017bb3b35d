#pragma once
// One optimisation of the scene's task, run off the UI thread so the editor stays live: the
// engine's OptimizationRun (the SimulationObjective, forward pass + adjoint per evaluation,
// minimised by any method makeOptimizer knows, over the chosen task parameters within their
// bounds). The UI can pause it,
// step it one evaluation at a time, resume or cancel it, and reads the loss and parameter
// history as evaluations arrive. The run works on a copy of the scene taken at start: applying
// its result to the document is the session's job (one undoable edit). No window: unit tested.

#include "EvaluationGate.h"

#include <weft/optim/OptimizationRun.h>
#include <weft/record/StepProgress.h>
#include <weft/scene/Scene.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace weft::editor {

class OptimizerRun {
 public:
  enum class Status { Idle, Running, Paused, Finished, Cancelled, Failed };

  struct Setup {
    std::string method = "lbfgsb";
    std::vector<std::string> parameters;  // JSON paths of the scene (the task's, or a subset)
    OptimizerSettings settings;
  };

  // One evaluation: its loss and the parameter values (physical units, not optimiser
  // coordinates), in the order of parameters().
  struct Sample {
    int evaluation = 0;
    long long steps = 0;
    double loss = 0.0;
    std::vector<double> values;
    bool hasGradient = false;
    double gradientError = 0.0;  // its estimated relative error, when hasGradient
    int unconvergedSteps = 0;    // its forward steps that stopped above solver.pd_tolerance
  };

  // Where the evaluation under way is, step by step (`active` false between evaluations).
  struct Progress {
    bool active = false;
    int evaluation = 0;  // 1-based, the one under way
    PassPhase phase = PassPhase::Forward;
    int pass = 1;  // the backward pass of its gradient (error control makes pairs)
    int done = 0, total = 0;
  };

  // The method names makeOptimizer accepts (probed by name, so a method added to the engine
  // shows up here without an editor change).
  static std::vector<std::string> methods();

  OptimizerRun();
  ~OptimizerRun();  // cancels and waits for the worker
  OptimizerRun(const OptimizerRun&) = delete;
  OptimizerRun& operator=(const OptimizerRun&) = delete;

  // Starts a run of `scene` (validated, with a task whose loss targets can be read). A running
  // run is cancelled first. `paused`: wait for step() or resume() before the first evaluation.
  // Returns an error text (unknown method, no parameters, a scene the objective refuses: contact,
  // unreadable targets, a value outside its bounds) and then leaves nothing running.
  std::string start(const Scene& scene, const Setup& setup, bool paused);
  void pause();
  void resume();
  void step(int evaluations = 1);  // pauses after that many more evaluations
  void cancel();                   // waits for the worker; the samples so far stay
  void wait();                     // until the worker has finished (do not call while paused)

  Status status() const;
  bool active() const { return status() == Status::Running || status() == Status::Paused; }
  static const char* statusName(Status status);
  std::string error() const;
  std::string stopReason() const;

  const std::string& method() const { return method_; }
  const std::vector<std::string>& parameters() const { return parameters_; }
  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }
  const std::vector<double>& initialValues() const { return initial_; }
  // The scene document the run started from.
  const nlohmann::json& startDocument() const { return startDocument_; }

  std::vector<Sample> samples() const;
  Progress progress() const;
  int evaluations() const;
  std::optional<Sample> best() const;  // the lowest loss so far
  // Forward steps of the run's evaluations so far that stopped at solver.pd_iterations above
  // solver.pd_tolerance: their gradients are those of unconverged steps (the panel warns).
  int unconvergedForwardSteps() const;
  // Gradients of the run so far whose estimated error missed solver.backward.accuracy, and the
  // largest estimate (diff/GradientErrorControl.h; the panel shows both).
  int gradientsMissingAccuracy() const;
  double largestGradientError() const;

 private:
  void join();

  std::string method_;
  std::vector<std::string> parameters_;
  std::vector<double> lower_, upper_, initial_;
  nlohmann::json startDocument_;

  std::unique_ptr<OptimizationRun> run_;
  OptimizerSettings settings_;
  std::unique_ptr<EvaluationGate> gate_;  // one per run: a cancelled gate stays cancelled
  std::thread worker_;

  mutable std::mutex mutex_;
  std::vector<Sample> samples_;
  int unconverged_ = 0;
  Progress progress_;
  int missingAccuracy_ = 0;
  double largestError_ = 0.0;
  std::string error_, stopReason_;
  std::atomic<Status> status_{Status::Idle};
};

}  // namespace weft::editor
