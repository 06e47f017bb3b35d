#include "EvaluationGate.h"

namespace weft::editor {

void EvaluationGate::enter() {
  std::unique_lock<std::mutex> lock(mutex_);
  waiting_ = true;
  changed_.wait(lock, [this] { return cancelled_ || !paused_ || allowance_ > 0; });
  waiting_ = false;
  if (cancelled_) throw EvaluationCancelled{};
  if (paused_) --allowance_;
}

void EvaluationGate::pause() {
  std::lock_guard<std::mutex> lock(mutex_);
  paused_ = true;
  allowance_ = 0;
}

void EvaluationGate::resume() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paused_ = false;
    allowance_ = 0;
  }
  changed_.notify_all();
}

void EvaluationGate::allow(int evaluations) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paused_ = true;
    allowance_ += evaluations > 0 ? evaluations : 0;
  }
  changed_.notify_all();
}

void EvaluationGate::cancel() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    cancelled_ = true;
  }
  changed_.notify_all();
}

void EvaluationGate::check() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (cancelled_) throw EvaluationCancelled{};
}

bool EvaluationGate::paused() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return paused_;
}

bool EvaluationGate::waiting() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return waiting_;
}

}  // namespace weft::editor
