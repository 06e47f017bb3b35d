#pragma once
// An orbit camera: it looks at `target` from `distance` away, turned by yaw about +Y and
// raised by pitch. Named views (front, side, top) and auto-framing of a scene's bounds make
// screenshots reproducible.

#include <weft/render/Bounds.h>

#include <Eigen/Core>

#include <string>

namespace weft::render {

enum class NamedView {
  Front,  // from +Z, looking along -Z
  Side,   // from +X, looking along -X
  Top,    // from +Y, looking down, -Z up in the image
  Auto    // a three-quarter view from the front-right and above
};

// "front", "side", "top", "auto"; returns false for anything else.
bool parseNamedView(const std::string& text, NamedView& view);

struct Camera {
  Vec3f target = Vec3f::Zero();
  float distance = 3.0f;
  float yawDeg = 0.0f;    // about +Y; 0 puts the camera on +Z
  float pitchDeg = 0.0f;  // above the target's horizontal plane, in [-90, 90]
  float fovYDeg = 35.0f;  // vertical field of view (perspective)
  bool orthographic = false;
  float orthoHalfHeight = 1.0f;  // half the visible height in scene units (orthographic)
  float nearPlane = 0.01f, farPlane = 100.0f;

  Vec3f eye() const;
  Vec3f backward() const;  // unit vector from the target to the eye
  Vec3f right() const;
  Vec3f up() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(float aspect) const;  // aspect = width / height

  // Interaction (the editor): turn, dolly and slide, keeping the camera upright.
  void orbit(float yawDegrees, float pitchDegrees);
  void zoom(float factor);                      // distance (or ortho size) times factor
  void pan(float rightAmount, float upAmount);  // in scene units
};

// Fits `bounds` into the view of `camera` (keeping its direction and lens): the target moves
// to the bounds' centre, the distance becomes the smallest that shows every corner with a
// margin, and the clipping planes enclose the scene with room for the ground.
void frameBounds(Camera& camera, const Bounds& bounds, float aspect, float margin = 1.08f);

// A named view framed on `bounds`.
Camera namedViewCamera(NamedView view, const Bounds& bounds, float aspect);

}  // namespace weft::render
