#include <weft/contact/BoxShape.h>

namespace weft {

bool BoxShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  const Vec3 local = rotation_.transpose() * (p - center_);
  const Vec3 excess = local.cwiseAbs() - half_;  // per axis: > 0 outside that slab
  Vec3 normalLocal;
  double distance;
  if (excess.maxCoeff() > 0.0) {
    // Outside: the distance gradient points from the nearest face, edge or corner; it is
    // continuous across the regions (the normal turns smoothly around edges and corners).
    const Vec3 outside = excess.cwiseMax(0.0).cwiseProduct(local.cwiseSign());
    distance = outside.norm();
    if (distance > reach) return false;
    normalLocal = outside / distance;
  } else {
    // Inside: the nearest face.
    int axis = 0;
    distance = excess.maxCoeff(&axis);
    normalLocal = Vec3::Zero();
    normalLocal[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
  }
  out.distance = distance;
  out.normal = rotation_ * normalLocal;
  out.point = p - distance * out.normal;
  return true;
}

}  // namespace weft
