#pragma once
// The "Optimise" tab: which of the task's parameters may change and within which bounds
// (task.bounds, edited in the document), the method (every name makeOptimizer knows) and its
// settings, and the run itself on a worker thread: start, pause, step one evaluation, resume,
// cancel; the loss against evaluations and each parameter's history as they arrive; and applying
// the best values to the document or reverting to the start values (each one undo step).

#include <map>
#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class OptimiserPanel {
 public:
  void draw(EditorSession& session, EditorApp& app);

 private:
  std::map<std::string, bool> excluded_;  // task parameters unticked by the user
  int method_ = 0;
  int maxEvaluations_ = 30;
  double learningRate_ = 0.05;
  int seed_ = 0;
};

}  // namespace weft::editor
