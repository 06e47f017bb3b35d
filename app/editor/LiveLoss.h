#pragma once
// The task loss of the cached run, shown live while targets are edited: the document's current
// task (its final targets from the sidecar when the editor holds them, every other term from
// its files, as the engine's TaskLoss reads them) applied to the motion in the simulation cache.
// Recomputed only when the document or the run changes. No window: unit tested.

#include "EditorDocument.h"
#include "SimulationCache.h"

#include <weft/diff/TaskLoss.h>
#include <weft/record/Trajectory.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace weft::editor {

struct LossValue {
  bool available = false;
  std::string
      note;  // why it is not available (no task, no complete run, a target that cannot be read)
  double total = 0.0;
  std::vector<std::pair<std::string, double>> terms;  // (term name, value)
};

class LiveLoss {
 public:
  const LossValue& evaluate(const EditorDocument& document, const SimulationCache& cache);

 private:
  long revision_ = -1, runId_ = -1;
  int frames_ = -1;
  LossValue value_;
  Trajectory trajectory_;  // the cached positions of the run `runId_`
  // The engine's loss over the terms read from files, kept while those terms do not change
  // (reading a recorded motion on every target drag would be wasted work).
  std::string fileTermsKey_;
  std::unique_ptr<TaskLoss> fileTerms_;
};

}  // namespace weft::editor
