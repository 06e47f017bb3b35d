#include <weft/contact/CapsuleShape.h>

#include <weft/contact/SphereShape.h>

#include <algorithm>

namespace weft {

bool CapsuleShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  const Vec3 axis = b_ - a_;
  const double s = std::clamp((p - a_).dot(axis) / axis.squaredNorm(), 0.0, 1.0);
  const Vec3 closest = a_ + s * axis;
  if ((p - closest).squaredNorm() > (radius_ + reach) * (radius_ + reach)) return false;
  sampleBall(closest, radius_, p, out);
  return true;
}

}  // namespace weft
