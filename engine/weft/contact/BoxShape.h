#pragma once
// A solid oriented box: centre, half extents, rotation (body axes in world columns).

#include <weft/contact/ObstacleShape.h>

namespace weft {

class BoxShape final : public ObstacleShape {
 public:
  BoxShape(const Vec3& center, const Vec3& halfExtents, const Mat3& rotation)
      : center_(center), half_(halfExtents), rotation_(rotation) {}
  const char* name() const override { return "box"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;

 private:
  Vec3 center_, half_;
  Mat3 rotation_;
};

}  // namespace weft
