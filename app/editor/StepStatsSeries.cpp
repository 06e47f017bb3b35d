#include "StepStatsSeries.h"

#include <algorithm>
#include <cmath>

namespace weft::editor {

void StepStatsSeries::update(const SimulationCache& cache) {
  if (cache.runId() != runId_) {
    runId_ = cache.runId();
    takeoff_.clear(), stick_.clear(), slip_.clear(), pdIterations_.clear(), log10Residual_.clear();
    unconverged_.clear();
    anyContact_ = false;
  }
  const int frames = cache.frameCount();
  for (int k = size() + 1; k < frames; ++k) {
    const auto frame = cache.frame(k);
    if (!frame) break;
    const StepStats& s = frame->stats;
    takeoff_.push_back(float(s.takeoff));
    stick_.push_back(float(s.stick));
    slip_.push_back(float(s.slip));
    pdIterations_.push_back(float(s.pdIterations));
    // A residual of exactly zero (a step with nothing to solve) is drawn at the plot's floor.
    log10Residual_.push_back(float(std::log10(std::max(s.residual, 1e-16))));
    anyContact_ = anyContact_ || s.takeoff + s.stick + s.slip > 0;
    if (!s.converged) unconverged_.push_back(k);
  }
}

}  // namespace weft::editor
