#pragma once
// The timeline's solver and contact history as plottable series, one value per cached step
// (states 1..N; state 0 has no step): contacts per Signorini-Coulomb branch, PD iterations
// (solves with P) and the residual the step ended with. Kept up to date incrementally while the
// simulation appends frames; rebuilt when a new run starts. No window: unit tested.

#include "SimulationCache.h"

#include <vector>

namespace weft::editor {

class StepStatsSeries {
 public:
  // Appends the frames cached since the last call (all of them after a new run).
  void update(const SimulationCache& cache);

  int size() const { return static_cast<int>(pdIterations_.size()); }
  const std::vector<float>& takeoff() const { return takeoff_; }
  const std::vector<float>& stick() const { return stick_; }
  const std::vector<float>& slip() const { return slip_; }
  const std::vector<float>& pdIterations() const { return pdIterations_; }
  // log10 of the residual (m/s^2): it spans decades, so a linear plot shows only its peaks.
  const std::vector<float>& log10Residual() const { return log10Residual_; }
  bool anyContact() const { return anyContact_; }
  // The states (1..N) whose step stopped at the iteration limit above the tolerance, in order:
  // the timeline marks each with a red tick.
  const std::vector<int>& unconvergedStates() const { return unconverged_; }

 private:
  long runId_ = -1;
  std::vector<float> takeoff_, stick_, slip_, pdIterations_, log10Residual_;
  std::vector<int> unconverged_;
  bool anyContact_ = false;
};

}  // namespace weft::editor
