#pragma once
// What the task's loss compares a run to, as the editor edits it: final-frame targets
// (FinalTargets.h; the editor holds them until the scene is saved), a recorded target motion
// (the trajectory term), a target shape from a mesh file, and the built-in hemline term; and
// the task loss of the cached run (LiveLoss.h). Positions are in metres; "shown" positions are
// the ones the viewport draws now (the cached frame, or the rest state).

#include "EditorDocument.h"
#include "FinalTargets.h"
#include "LiveLoss.h"
#include "MeshImport.h"
#include "Selection.h"
#include "SimulationCache.h"
#include "ViewportFrame.h"

#include <weft/render/Camera.h>

#include <functional>
#include <string>
#include <vector>

namespace weft::editor {

class TaskTargets {
 public:
  TaskTargets(EditorDocument& document, const SimulationCache& cache, const Selection& selection,
              ViewportFrame& viewport, const render::Camera& camera);

  std::vector<FinalTarget> all() const { return finalTargets(document_.sidecar()); }
  std::string setTargetsFromSelection();  // a target at each selected vertex's shown position
  std::string setTarget(int node, const Vec3& position, const std::string& coalesceKey = "");
  std::string moveTargets(const std::vector<int>& nodes, const Vec3& delta,
                          const std::string& coalesceKey = "");
  // Moves the targets of `nodes` in the camera's image plane by a pixel offset (x right, y down)
  // of a width x height view, each at its own depth: what dragging them in the viewport does.
  std::string dragTargets(const std::vector<int>& nodes, float dx, float dy, int width, int height,
                          const std::string& coalesceKey = "");
  std::string removeTargets(const std::vector<int>& nodes);  // empty: all
  // A recorded motion (a positions.npy of `weft simulate`, [states >= steps + 1, vertices, 3])
  // as the task's trajectory term; checked by the engine's TaskLoss before it is added.
  std::string loadTargetMotion(const std::string& file);
  std::string removeTargetMotion();
  // The final shape from a mesh file: a final-frame target for every vertex of the cloth whose
  // mesh has as many vertices (the first such cloth), at the file's vertex positions placed as
  // that cloth's own mesh is (its `scale` and `transform`): a target shape exported in the same
  // frame and units as the garment's file. One undo step; error text or "".
  std::string loadTargetMesh(const std::string& file);
  // The built-in hemline term (task.loss.hemline, DiffCloth Eq. 34): the selected vertices'
  // mean squared height gap to `height` (m) at the last state. One undo step each.
  std::string setHemline(double height);
  std::string removeHemline();
  // The task loss of the cached run (LiveLoss.h).
  const LossValue& liveLoss();

  // Writes the final-target .npy the scene saved as `sceneFile` names (when the editor holds
  // targets it owns); a warning text, "" normally, e.g. when the scene does not validate.
  std::string writeTargets(const std::string& sceneFile);
  // Calls `use` with the document's scene whose final term reads the targets the editor holds
  // (from a private temporary file, removed afterwards): what the engine's TaskLoss needs.
  std::string withHeldTargets(const std::function<std::string(const Scene&)>& use);

 private:
  std::string editTargets(const std::string& label, std::vector<FinalTarget> targets,
                          const std::string& coalesceKey = "");
  // Sets or removes one term of task.loss (one undo step); removing the last term removes the
  // task unless it names parameters. `what` names the term in the error when it is absent.
  std::string setLossTerm(const std::string& term, const nlohmann::json& value,
                          const std::string& label);
  std::string removeLossTerm(const std::string& term, const std::string& label,
                             const std::string& what);

  EditorDocument& document_;
  const SimulationCache& cache_;
  const Selection& selection_;
  ViewportFrame& viewport_;
  const render::Camera& camera_;
  LiveLoss liveLoss_;
};

}  // namespace weft::editor
