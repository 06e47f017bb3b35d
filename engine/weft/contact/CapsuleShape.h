#pragma once
// A capsule: all points within `radius` of the segment a-b (smooth everywhere outside).

#include <weft/contact/ObstacleShape.h>

namespace weft {

class CapsuleShape final : public ObstacleShape {
 public:
  CapsuleShape(const Vec3& a, const Vec3& b, double radius) : a_(a), b_(b), radius_(radius) {}
  const char* name() const override { return "capsule"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;

 private:
  Vec3 a_, b_;
  double radius_;
};

}  // namespace weft
