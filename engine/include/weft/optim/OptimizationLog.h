#pragma once
// Every evaluation an optimiser made, in order, with the simulated steps and wall-clock seconds
// spent so far and whether it computed a gradient: the rows of `loss.csv` and of `weft bench
// applications`, and the best point seen (what an optimiser returns: line searches and
// evolution strategies evaluate trial points that may be worse than the last accepted one).

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace weft {

struct LogEntry {
  int evaluation = 0;    // 1-based
  long long steps = 0;   // simulated steps so far, this evaluation included
  double seconds = 0.0;  // wall-clock seconds since the run started, this evaluation included
  double loss = 0.0;
  bool hasGradient = false;    // a gradient evaluation (else value only, `gradient` empty)
  Eigen::VectorXd x;           // optimiser coordinates
  Eigen::VectorXd gradient;    // dL/dx in optimiser coordinates, when hasGradient
  double gradientError = 0.0;  // its estimated relative error (Objective::lastGradientError)
};

class OptimizationLog {
 public:
  using Observer = std::function<void(const LogEntry&)>;
  void setObserver(Observer observer) { observer_ = std::move(observer); }
  void add(LogEntry entry);
  // Forgets the entries (a new run), keeping the observer.
  void clear() { entries_.clear(), best_ = 0; }
  const std::vector<LogEntry>& entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }
  // The entry with the lowest loss (the first of equals); requires !empty().
  const LogEntry& best() const { return entries_[best_]; }
  long long steps() const { return entries_.empty() ? 0 : entries_.back().steps; }

 private:
  std::vector<LogEntry> entries_;
  std::size_t best_ = 0;
  Observer observer_;
};

}  // namespace weft
