#pragma once
// The task's parameters (task.parameters: what the optimiser may change) and the optimiser run
// over them (OptimizerRun.h), started on a copy of the current document; its result written
// back into the document.

#include "EditorDocument.h"
#include "OptimizerRun.h"
#include "TaskTargets.h"

#include <string>
#include <vector>

namespace weft::editor {

class ParameterOptimisation {
 public:
  ParameterOptimisation(EditorDocument& document, TaskTargets& targets);

  // `path` must be one of differentiableParameterPaths (diff/SceneParameter.h) and the task
  // must have a loss (a task without one does not validate); removing drops the path's bounds
  // too. One undo step each; "" on success, else why not.
  std::string addParameter(const std::string& path);
  std::string removeParameter(const std::string& path);

  OptimizerRun& optimizer() { return optimizer_; }
  const OptimizerRun& optimizer() const { return optimizer_; }
  // Targets the editor holds but has not saved yet are written to a private temporary file for
  // the run.
  std::string start(const OptimizerRun::Setup& setup, bool paused);
  // Writes the best values of the run into the document (one undo step), or its start values.
  std::string applyResult();
  std::string revertToStart();

 private:
  std::string setParameterValues(const std::string& label, const std::vector<double>& values);

  EditorDocument& document_;
  TaskTargets& targets_;
  OptimizerRun optimizer_;
};

}  // namespace weft::editor
