#pragma once
// The loss gradient of the cached run under the task as it is now: dL/dx_n of every state (the
// backward pass of diff/Backpropagation.h over the cached states and contacts), for the vertex
// inspector. Computed on a worker thread (a backward pass costs about as much as the run) and
// stamped with the cache run and document revision it was computed for, so that any later
// edit or run makes it stale.

#include "EditorDocument.h"
#include "SimulationCache.h"
#include "TaskTargets.h"

#include <weft/core/Types.h>

#include <future>
#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

class StateGradients {
 public:
  StateGradients(const EditorDocument& document, const SimulationCache& cache,
                 TaskTargets& targets);

  // Starts the backward pass and returns at once: error text, or "" when it started. collect()
  // takes the result once it is there.
  std::string compute();
  bool computing() const { return job_.valid(); }
  // Takes the worker's result when it is ready (called once per UI frame).
  void collect();
  // Why the last computation failed ("" when it did not).
  const std::string& error() const { return error_; }
  // dL/dx of `node` at `state`, once computed for this cache and task (nullopt otherwise).
  std::optional<Vec3> at(int node, int state) const;

 private:
  const EditorDocument& document_;
  const SimulationCache& cache_;
  TaskTargets& targets_;
  std::future<std::vector<NodeMatrix>> job_;
  long jobRun_ = -1, jobRevision_ = -1;
  std::vector<NodeMatrix> gradients_;
  long gradientsRun_ = -1;
  long gradientsRevision_ = -1;
  std::string error_;
};

}  // namespace weft::editor
