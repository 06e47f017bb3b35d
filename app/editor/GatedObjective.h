#pragma once
// An Objective that asks a gate before every evaluation, so an optimiser running on a worker
// thread can be paused, stepped one evaluation at a time, or cancelled from the UI without the
// optimiser knowing: the methods (L-BFGS-B, Adam, ...) just see an evaluation that takes longer.
// Cancelling throws EvaluationCancelled out of evaluate(); it is deliberately not a
// std::exception, so no method mistakes it for a failed line search and carries on.

#include <weft/optim/Objective.h>

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
  bool paused() const;
  // True when the worker is blocked in enter() (paused, nothing allowed).
  bool waiting() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool paused_ = false, cancelled_ = false, waiting_ = false;
  int allowance_ = 0;
};

class GatedObjective final : public Objective {
 public:
  GatedObjective(Objective& inner, EvaluationGate& gate) : inner_(inner), gate_(gate) {}
  int dimension() const override { return inner_.dimension(); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) override {
    gate_.enter();
    return inner_.evaluate(x, gradient);
  }
  double value(const Eigen::VectorXd& x) override {
    gate_.enter();
    return inner_.value(x);
  }
  long long stepsPerEvaluation() const override { return inner_.stepsPerEvaluation(); }
  long long stepsPerValue() const override { return inner_.stepsPerValue(); }

 private:
  Objective& inner_;
  EvaluationGate& gate_;
};

}  // namespace weft::editor
