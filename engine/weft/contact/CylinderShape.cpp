#include <weft/contact/CylinderShape.h>

#include <cmath>

namespace weft {

CylinderShape::CylinderShape(const Vec3& a, const Vec3& b, double radius)
    : middle_(0.5 * (a + b)), axis_((b - a).normalized()), halfLength_(0.5 * (b - a).norm()), radius_(radius) {
  fallbackRadial_ = axis_.cross(std::abs(axis_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
}

bool CylinderShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  const Vec3 offset = p - middle_;
  const double axial = offset.dot(axis_);
  const Vec3 radialVector = offset - axial * axis_;
  const double radial = radialVector.norm();
  const Vec3 radialDir = radial > 1e-300 ? Vec3(radialVector / radial) : fallbackRadial_;
  const Vec3 axialDir = axial >= 0.0 ? axis_ : Vec3(-axis_);
  const double excessAxial = std::abs(axial) - halfLength_, excessRadial = radial - radius_;
  double distance;
  if (excessAxial > 0.0 || excessRadial > 0.0) {
    // Outside: distance to the side, the cap or the rim circle, whichever is nearest.
    const double a = std::max(excessAxial, 0.0), r = std::max(excessRadial, 0.0);
    distance = std::hypot(a, r);
    if (distance > reach) return false;
    out.normal = (r * radialDir + a * axialDir) / distance;
  } else if (excessAxial > excessRadial) {
    distance = excessAxial;
    out.normal = axialDir;
  } else {
    distance = excessRadial;
    out.normal = radialDir;
  }
  out.distance = distance;
  out.point = p - distance * out.normal;
  return true;
}

}  // namespace weft
