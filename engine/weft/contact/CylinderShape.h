#pragma once
// A solid capped cylinder of `radius` around the segment a-b (flat end caps).

#include <weft/contact/ObstacleShape.h>

namespace weft {

class CylinderShape final : public ObstacleShape {
 public:
  CylinderShape(const Vec3& a, const Vec3& b, double radius);
  const char* name() const override { return "cylinder"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;

 private:
  Vec3 middle_, axis_;  // axis_: unit, a -> b
  double halfLength_, radius_;
  Vec3 fallbackRadial_;  // a unit vector orthogonal to the axis, for points on the axis
};

}  // namespace weft
