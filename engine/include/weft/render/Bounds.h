#pragma once
// An axis-aligned box around what a frame shows, for framing the camera and sizing the ground.

#include <weft/render/RenderScene.h>

#include <limits>

namespace weft::render {

struct Bounds {
  Vec3f min = Vec3f::Constant(std::numeric_limits<float>::infinity());
  Vec3f max = Vec3f::Constant(-std::numeric_limits<float>::infinity());

  bool empty() const { return !(min.array() <= max.array()).all(); }
  void extend(const Vec3f& p);
  void extend(const Bounds& b);
  Vec3f center() const { return 0.5f * (min + max); }
  // Half the diagonal; a small positive number for an empty or point-like box.
  float radius() const;
};

// Everything with a finite extent: cloth, finite obstacles, markers, curves, ghosts. Planes are
// unbounded and left out (they are drawn sized to the rest).
Bounds sceneBounds(const RenderScene& scene);

// How a plane is drawn for a frame with these bounds: a square of this half size, centred on the
// bounds' centre projected onto the plane, with sides along perpendicularFrame(normal)
// (ShapeTessellation.h). What picking treats as the plane's extent.
float planeHalfSize(const Bounds& bounds);

}  // namespace weft::render
