#pragma once
// The "Targets" tab: final-frame targets for chosen vertices (set at the selected vertices'
// shown positions, typed per target, moved by an offset, or dragged in the viewport with Alt
// held), the final term's weight, a recorded target motion (the trajectory term), a target
// shape from a mesh file (final targets at every vertex), the built-in hemline term, and the
// task loss of the cached run, updated live as targets change.

#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class TargetPanel {
 public:
  void draw(EditorSession& session, EditorApp& app);

 private:
  double offset_[3] = {0.0, 0.05, 0.0};
  char motionPath_[1024] = {};
  double hemlineHeight_ = 0.7;
  int editSerial_ = 0;  // numbers edits of a target field, so one typed value is one undo step
};

}  // namespace weft::editor
