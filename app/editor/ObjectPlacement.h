#pragma once
// The object the transform gizmo places (Gizmo.h): an obstacle, a cloth or a handle
// ("obstacles.N", "cloths.N", "cloths.N.attachments.M"; "" for none), chosen by path or by
// Ctrl+click, and its drags. Obstacles and cloths move in the document, each drag one undo
// step; a handle's drag moves its offset at the playback frame (pending until keyed), and its
// keys (attachments.M.trajectory.keyframes) are set, deleted and jumped to here.

#include "EditorDocument.h"
#include "Gizmo.h"
#include "Placement.h"
#include "SimulationCache.h"
#include "Timeline.h"
#include "ViewportFrame.h"

#include <weft/contact/ContactObstacle.h>
#include <weft/core/Types.h>
#include <weft/render/Camera.h>

#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

class ObjectPlacement {
 public:
  ObjectPlacement(EditorDocument& document, Timeline& timeline, const render::Camera& camera,
                  ViewportFrame& viewport, const SimulationCache& cache);

  const EditorObject& activeObject() const { return active_; }
  std::string setActiveObject(const std::string& path);
  // Ctrl+click: the obstacle or cloth under the pixel of a width x height view (the nearest, as
  // the viewport shows it: ObjectPicking.h) becomes the active object; a click that meets
  // nothing takes the gizmo off, as Esc does. Returns an error text ("" also for a click on
  // nothing; activeObject() says what was picked), e.g. when the object shown is no longer in
  // the document.
  std::string clickObject(float x, float y, int width, int height);
  // The gizmo of the active object in a width x height view; nullopt when there is none or the
  // scene does not validate (its placement is read from the validated scene).
  std::optional<Gizmo> gizmo(int width, int height) const;
  GizmoHandle pickGizmo(float x, float y, int width, int height) const;
  // A drag from pixel (x, y) of the handle, then the mouse's positions, then the release.
  std::string beginGizmoDrag(GizmoHandle handle, float x, float y, int width, int height);
  std::string dragGizmo(float x, float y);
  void endGizmoDrag();
  GizmoHandle draggedHandle() const { return drag_ ? drag_->drag.handle() : GizmoHandle::None; }

  // Keys of the active handle (attachments.M.trajectory.keyframes, or a Hermite spline's knots).
  std::vector<HandleKey> keys() const;
  // The active handle's offset at the playback frame: the one dragged or typed there (pending,
  // until setKey records it), else the trajectory's. nullopt without an active handle or a
  // valid scene.
  std::optional<Vec3> handleOffset() const;
  bool handleOffsetPending() const;
  std::string setHandleOffset(const Vec3& offset);  // typed: pending, like a drag
  // Records the handle's offset as a key at the playback frame's time (replacing a key within
  // half a step of it), or deletes that key; one undo step each, and the cache goes stale.
  std::string setKey();
  std::string deleteKey();
  // Moves the playback frame to the next (+1) or previous (-1) key of the active handle.
  std::string jumpToKey(int direction);

  // An undo or a removal can take the active object away (or turn a handle into a fixed pin):
  // it is then dropped. Called once per UI frame.
  void dropStaleActiveObject();
  // A new document: no active object, drag or pending offset.
  void reset();

 private:
  // The active object's centre in the scene's own (rest) coordinates, from the validated scene;
  // nullopt when it cannot be found. A handle's is where its keys put it at the shown time.
  std::optional<Vec3> objectOrigin() const;
  // Where a moving obstacle is shown at the timeline's time (its motion's pose; identity for
  // everything else): the gizmo sits at shownPose().apply(objectOrigin()).
  RigidPose shownPose() const;
  std::string handleError() const;  // why keys cannot be edited now ("" when they can)

  EditorDocument& document_;
  Timeline& timeline_;
  const render::Camera& camera_;
  ViewportFrame& viewport_;
  const SimulationCache& cache_;
  EditorObject active_;
  struct DragState {
    GizmoDrag drag;
    EditorObject object;
    nlohmann::json start;  // the object's entry when the drag began
    Vec3 centre = Vec3::Zero();
    Vec3 startOffset = Vec3::Zero();  // a handle's offset when the drag began
    std::string label, coalesceKey;
  };
  std::optional<DragState> drag_;
  int dragCount_ = 0;  // numbers gizmo drags, so each drag is one undo step
  // A handle offset dragged or typed but not keyed yet: it belongs to one handle at one frame.
  struct PendingOffset {
    EditorObject object;
    int frame = -1;
    Vec3 offset = Vec3::Zero();
  };
  std::optional<PendingOffset> pending_;
};

}  // namespace weft::editor
