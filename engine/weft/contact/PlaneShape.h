#pragma once
// A half-space: everything below the plane through `point` with unit normal `normal`.

#include <weft/contact/ObstacleShape.h>

namespace weft {

class PlaneShape final : public ObstacleShape {
 public:
  PlaneShape(const Vec3& point, const Vec3& normal) : point_(point), normal_(normal.normalized()) {}
  const char* name() const override { return "plane"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;

 private:
  Vec3 point_, normal_;
};

}  // namespace weft
