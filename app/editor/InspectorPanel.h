#pragma once
// The "Inspect" tab: contact debugging on the cached run. The focused vertex's position,
// velocity, Signorini-Coulomb branch and contacts (what it touches, normal, impulse, mean force)
// at the playback state; the overlay switches (branch colours, force arrows); and per-step plots
// of the contacts per branch, PD iterations and the residual, with the current state marked.

#include <string>

namespace weft::editor {

class EditorSession;

class InspectorPanel {
 public:
  void draw(EditorSession& session);

 private:
  std::string gradientError_;  // why the last "Compute loss gradient" failed
};

}  // namespace weft::editor
