#pragma once
// How a handle (moving attachment) moves: a translation given by keyframes (piecewise linear)
// or by a cubic Hermite spline (as in DiffCloth's Hat and Sock tasks), optionally combined
// with a constant-rate rotation about an axis (a twirling waist). Times are in seconds from
// the start of the simulation; outside the key range the end values hold.

#include <weft/core/Types.h>

#include <vector>

namespace weft {

struct HandleTrajectory {
  enum class Kind { Keyframes, Hermite };
  Kind kind = Kind::Keyframes;
  std::vector<double> times;    // strictly increasing
  std::vector<Vec3> offsets;    // translation at each time (keyframes or spline points)
  std::vector<Vec3> tangents;   // d offset / dt at each time (Hermite only), m/s
  bool rotates = false;
  Vec3 rotationCenter = Vec3::Zero();
  Vec3 rotationAxis = Vec3::UnitY();  // unit
  double rotationRateDeg = 0.0;       // degrees per second

  Vec3 offset(double t) const;
  // Target of a vertex whose rest (initial) position is `rest`.
  Vec3 target(const Vec3& rest, double t) const;
};

}  // namespace weft
