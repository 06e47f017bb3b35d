#pragma once
// A gate the optimisation run enters before every evaluation (OptimizationRun's
// beforeEvaluation), so an optimiser running on a worker thread can be paused, stepped one
// evaluation at a time, or cancelled from the UI without the optimiser knowing: the methods
// (L-BFGS-B, Adam, ...) just see an evaluation that takes longer.
// Cancelling throws EvaluationCancelled out of enter(), so out of the evaluation; it is not a
// std::exception, so no method mistakes it for a failed line search and carries on.

#include <condition_variable>
#include <mutex>

namespace weft::editor {

struct EvaluationCancelled {};

class EvaluationGate {
 public:
  // Blocks while paused with no evaluations allowed; consumes one allowance when paused.
  // Throws EvaluationCancelled once cancelled.
  void enter();
  void pause();
  void resume();
  void allow(int evaluations);  // while paused: let this many more evaluations run
  void cancel();
  // Throws EvaluationCancelled once cancelled: called between the steps of an evaluation, so a
  // cancel takes effect within one step instead of at the next evaluation.
  void check() const;
  bool paused() const;
  // True when the worker is blocked in enter() (paused, nothing allowed).
  bool waiting() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool paused_ = false, cancelled_ = false, waiting_ = false;
  int allowance_ = 0;
};

}  // namespace weft::editor
