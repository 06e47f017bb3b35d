#include <weft/contact/PlaneShape.h>

namespace weft {

bool PlaneShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  const double d = normal_.dot(p - point_);
  if (d > reach) return false;
  out.distance = d;
  out.normal = normal_;
  out.point = p - d * normal_;
  return true;
}

}  // namespace weft
