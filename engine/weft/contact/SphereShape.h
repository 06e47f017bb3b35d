#pragma once
// A solid ball. Its normal (p - c)/|p - c| varies smoothly over the surface, which is what
// makes the contact dynamics continuous in DiffCloth's Fig. 2.

#include <weft/contact/ObstacleShape.h>

namespace weft {

class SphereShape final : public ObstacleShape {
 public:
  SphereShape(const Vec3& center, double radius) : center_(center), radius_(radius) {}
  const char* name() const override { return "sphere"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;

 private:
  Vec3 center_;
  double radius_;
};

// Shared by the round shapes: the sample of a ball of `radius` around `center`. A point at the
// centre gets the normal +Y (any direction is a valid gradient there).
void sampleBall(const Vec3& center, double radius, const Vec3& p, SurfaceSample& out);

}  // namespace weft
