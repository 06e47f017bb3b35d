#pragma once
// The "Scene" tab: time step and solver, cloths (mesh, placement, material, self-collision,
// attachments), gravity and wind, obstacles, and the vertex selection (pin it, make a handle of
// it, select a border loop or a band). Every field edits the document through DocumentFields.

#include "DocumentFields.h"

#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class ScenePanel {
 public:
  ScenePanel(EditorSession& session, EditorApp& app);
  void draw();

 private:
  void timePanel();
  void clothPanel();
  void effectsPanel();
  void obstaclePanel();
  void selectionPanel();
  // The "gizmo" button toggling which object the viewport's gizmo places.
  void placeButton(const std::string& path);

  EditorSession& session_;
  EditorApp& app_;
  DocumentFields fields_;
  int bandAxis_ = 1;  // the Selection panel's band: axis (y) and range (m)
  double band_[2] = {0.9, 1.1};
};

}  // namespace weft::editor
