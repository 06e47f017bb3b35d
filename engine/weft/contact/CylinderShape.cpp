#include <weft/contact/CylinderShape.h>

#include <algorithm>
#include <cmath>

namespace weft {

CylinderShape::CylinderShape(const Vec3& a, const Vec3& b, double radius)
    : middle_(0.5 * (a + b)),
      axis_((b - a).normalized()),
      halfLength_(0.5 * (b - a).norm()),
      radius_(radius) {
  fallbackRadial_ =
      axis_.cross(std::abs(axis_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
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

bool CylinderShape::sampleMoved(const Vec3& p, const Vec3& from, double reach,
                                SurfaceSample& out) const {
  const Vec3 offset = p - middle_, startOffset = from - middle_;
  const double axial = offset.dot(axis_), startAxial = startOffset.dot(axis_);
  const Vec3 radialVector = offset - axial * axis_, startRadial = startOffset - startAxial * axis_;
  const double radial = radialVector.norm();
  const bool inside = std::abs(axial) <= halfLength_ && radial <= radius_;
  const bool startedOutside = std::abs(startAxial) > halfLength_ || startRadial.norm() > radius_;
  if (!inside || !startedOutside) return sample(p, reach, out);
  // The solid is the slab |axial| <= h intersected with the infinite cylinder radial <= r; the
  // segment enters it where it enters the later of the two (t in (0, 1], t = 1 at p).
  double capEntry = -1.0, sideEntry = -1.0;
  const double side = startAxial >= 0.0 ? 1.0 : -1.0;
  const double above = side * startAxial - halfLength_;
  if (above > 0.0) capEntry = above / (side * startAxial - side * axial);  // denominator >= above
  const double startExcess = startRadial.squaredNorm() - radius_ * radius_;
  if (startExcess > 0.0) {
    // |q0 + t d|^2 = r^2 with q0 outside and q0 + d inside: the smaller root, in (0, 1].
    const Vec3 d = radialVector - startRadial;
    const double a = d.squaredNorm(), b = startRadial.dot(d);
    sideEntry = (-b - std::sqrt(std::max(b * b - a * startExcess, 0.0))) / a;
  }
  if (capEntry >= sideEntry) {
    out.normal = side * axis_;
    out.distance = side * axial - halfLength_;
  } else {
    // Through the side: its normal at p (or, on the axis, where the path crossed the side).
    const Vec3 entry = startRadial + sideEntry * (radialVector - startRadial);
    out.normal = radial > 1e-12 * radius_ ? Vec3(radialVector / radial) : Vec3(entry.normalized());
    out.distance = radial - radius_;
  }
  out.point = p - out.distance * out.normal;
  return true;
}

}  // namespace weft
