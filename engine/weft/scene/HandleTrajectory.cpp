#include <weft/scene/HandleTrajectory.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace weft {

namespace {

struct HermiteBasis {
  double h00, h10, h01, h11;
};

// Cubic Hermite basis on the unit interval (tangent weights not yet scaled by the interval).
HermiteBasis hermiteBasis(double s) {
  const double s2 = s * s, s3 = s2 * s;
  return {2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2};
}

}  // namespace

HandleTrajectory::Segment HandleTrajectory::segment(double t) const {
  Segment seg;
  if (t <= times.front()) return seg;
  if (t >= times.back()) {
    seg.first = static_cast<int>(times.size()) - 1;
    return seg;
  }
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  seg.first = static_cast<int>(it - times.begin()) - 1;
  seg.dt = times[seg.first + 1] - times[seg.first];
  seg.s = (t - times[seg.first]) / seg.dt;
  return seg;
}

Vec3 HandleTrajectory::offset(double t) const {
  if (times.empty()) return Vec3::Zero();
  const Segment seg = segment(t);
  const std::size_t i = static_cast<std::size_t>(seg.first);
  if (seg.dt == 0.0) return offsets[i];  // held end point
  const double s = seg.s, dt = seg.dt;
  if (kind == Kind::Keyframes) return (1.0 - s) * offsets[i] + s * offsets[i + 1];
  // Cubic Hermite basis on [t_i, t_{i+1}] with tangents scaled by the interval length.
  const HermiteBasis b = hermiteBasis(s);
  return b.h00 * offsets[i] + b.h10 * dt * tangents[i] + b.h01 * offsets[i + 1] +
         b.h11 * dt * tangents[i + 1];
}

double HandleTrajectory::controlWeight(double t, Control control, int knot) const {
  if (times.empty()) return 0.0;
  const Segment seg = segment(t);
  if (seg.dt == 0.0) return control == Control::Offset && knot == seg.first ? 1.0 : 0.0;
  if (knot != seg.first && knot != seg.first + 1) return 0.0;
  const bool start = knot == seg.first;
  if (kind == Kind::Keyframes) {
    if (control == Control::Tangent) return 0.0;
    return start ? 1.0 - seg.s : seg.s;
  }
  const HermiteBasis b = hermiteBasis(seg.s);
  if (control == Control::Offset) return start ? b.h00 : b.h01;
  return seg.dt * (start ? b.h10 : b.h11);
}

Vec3 HandleTrajectory::target(const Vec3& rest, double t) const {
  Vec3 p = rest;
  if (rotates) {
    const double angle = rotationRateDeg * M_PI / 180.0 * t;
    p = rotationCenter + Eigen::AngleAxisd(angle, rotationAxis) * (rest - rotationCenter);
  }
  return p + offset(t);
}

}  // namespace weft
