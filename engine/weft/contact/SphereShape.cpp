#include <weft/contact/SphereShape.h>

namespace weft {

void sampleBall(const Vec3& center, double radius, const Vec3& p, SurfaceSample& out) {
  const Vec3 offset = p - center;
  const double r = offset.norm();
  out.normal = r > 1e-300 ? Vec3(offset / r) : Vec3::UnitY();
  out.distance = r - radius;
  out.point = center + radius * out.normal;
}

bool SphereShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  if ((p - center_).squaredNorm() > (radius_ + reach) * (radius_ + reach)) return false;
  sampleBall(center_, radius_, p, out);
  return true;
}

}  // namespace weft
