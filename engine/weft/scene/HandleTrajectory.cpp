#include <weft/scene/HandleTrajectory.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace weft {

Vec3 HandleTrajectory::offset(double t) const {
  if (times.empty()) return Vec3::Zero();
  if (t <= times.front()) return offsets.front();
  if (t >= times.back()) return offsets.back();
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - times.begin()) - 1;
  const double dt = times[i + 1] - times[i];
  const double s = (t - times[i]) / dt;
  if (kind == Kind::Keyframes) return (1.0 - s) * offsets[i] + s * offsets[i + 1];
  // Cubic Hermite basis on [t_i, t_{i+1}] with tangents scaled by the interval length.
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  return h00 * offsets[i] + h10 * dt * tangents[i] + h01 * offsets[i + 1] + h11 * dt * tangents[i + 1];
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
