#pragma once
// The viewport's transform gizmo as plain geometry: three translate arrows along the world axes
// and, for objects that can turn, three rotate rings about them, centred on the object being
// placed and kept at a constant size on screen; picking (a ray against the handles, thickened
// to a few pixels) and the drag arithmetic (mouse motion projected onto the axis on screen, or
// the angle swept about the centre). No GL, no window: unit tested. EditorSession decides what
// a drag does to the document, EditorApp draws the handles over the viewport image.

#include "Selection.h"

#include <weft/render/Camera.h>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

enum class GizmoHandle { None = -1, TranslateX, TranslateY, TranslateZ, RotateX, RotateY, RotateZ };

// "translate_x" ... "rotate_z" (the script's names), "none".
const char* gizmoHandleName(GizmoHandle handle);
bool parseGizmoHandle(const std::string& text, GizmoHandle& handle);
inline bool isRotation(GizmoHandle h) {
  return h >= GizmoHandle::RotateX;
}
// 0, 1, 2 for the X, Y, Z handles (-1 for None).
inline int gizmoAxis(GizmoHandle h) {
  return h == GizmoHandle::None ? -1 : static_cast<int>(h) % 3;
}

class Gizmo {
 public:
  // Sizes in pixels: constant on screen whatever the distance, so the handles stay grabbable.
  static constexpr float kArrowPixels = 80.0f;  // arrow length
  static constexpr float kArrowStart =
      0.2f;  // arrows start this fraction out (the centre is crowded)
  static constexpr float kRingPixels =
      100.0f;  // ring radius: outside the arrows, so they never cross
  static constexpr float kPickPixels =
      6.0f;  // how far from a handle's centre line a ray still grabs it
  static constexpr int kRingSegments = 64;

  // A gizmo at `origin` seen through `camera` in a width x height view; `rotates` adds the rings.
  Gizmo(const Eigen::Vector3f& origin, bool rotates, const render::Camera& camera, int width,
        int height);

  const Eigen::Vector3f& origin() const { return origin_; }
  bool rotates() const { return rotates_; }
  bool has(GizmoHandle h) const { return h != GizmoHandle::None && (!isRotation(h) || rotates_); }
  const render::Camera& camera() const { return camera_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // World length of one pixel at the gizmo's depth.
  float metresPerPixel() const { return metresPerPixel_; }

  // A handle's centre line in world space: an arrow's shaft (two points, base then tip), or a
  // ring as a closed polyline (the first point repeated at the end).
  std::vector<Eigen::Vector3f> polyline(GizmoHandle handle) const;
  // Where a handle is drawn in pixels (x right, y down); points behind the camera are dropped.
  std::vector<Eigen::Vector2f> screenPolyline(GizmoHandle handle) const;

  // The handle a ray grabs: of the handles whose thickened centre line the ray passes within
  // kPickPixels of, the one nearest the camera, arrows before rings. None when it misses them all.
  GizmoHandle pick(const Ray& ray) const;
  GizmoHandle pickPixel(float x, float y) const;
  // A pixel that grabs `handle` (three quarters along an arrow; the ring's point farthest from
  // the centre on screen), what a script presses the mouse on. nullopt when it is not visible.
  std::optional<Eigen::Vector2f> grabPixel(GizmoHandle handle) const;

 private:
  Eigen::Vector3f origin_;
  bool rotates_;
  render::Camera camera_;
  int width_, height_;
  float metresPerPixel_;
};

// One drag of a handle, from the pixel where the mouse was pressed. For an arrow the amount is
// the translation along its axis in metres: the mouse motion projected onto the axis's direction
// on screen, divided by the axis's length on screen per metre. For a ring it is the angle in
// radians turned about the axis (right-handed), swept by the mouse about the gizmo's centre on
// screen; it keeps counting past half a turn.
class GizmoDrag {
 public:
  // nullopt when the handle cannot be dragged from this view: an arrow pointing at the camera
  // (it has no direction on screen), or a pixel on the gizmo's centre.
  static std::optional<GizmoDrag> begin(const Gizmo& gizmo, GizmoHandle handle,
                                        const Eigen::Vector2f& pixel);

  GizmoHandle handle() const { return handle_; }
  // The amount for the mouse at `pixel` (since the start).
  double update(const Eigen::Vector2f& pixel);
  double amount() const { return amount_; }

 private:
  GizmoHandle handle_ = GizmoHandle::None;
  Eigen::Vector2f start_, centre_, previous_;
  Eigen::Vector2f pixelsPerMetre_;  // the axis on screen (translation)
  float sign_ = 1.0f;               // +1 when the rotation axis points at the camera
  double amount_ = 0.0;
};

// The scene contract's rotate_deg (about X, then Y, then Z: R = Rz Ry Rx) of a rotation matrix:
// the inverse of RigidTransform::rotation(). Of the angle triples that give `rotation`, the one
// nearest `near` (each angle within half a turn of it): what the document held before a drag, so
// that the numbers change continuously. At gimbal lock (Y angle +-90) the Z angle is 0 and X
// takes the whole turn about the shared axis.
Eigen::Vector3d eulerXyzDegrees(const Eigen::Matrix3d& rotation,
                                const Eigen::Vector3d& near = Eigen::Vector3d::Zero());

}  // namespace weft::editor
