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
  std::vector<double> times;   // strictly increasing
  std::vector<Vec3> offsets;   // translation at each time (keyframes or spline points)
  std::vector<Vec3> tangents;  // d offset / dt at each time (Hermite only), m/s
  bool rotates = false;
  Vec3 rotationCenter = Vec3::Zero();
  Vec3 rotationAxis = Vec3::UnitY();  // unit
  double rotationRateDeg = 0.0;       // degrees per second

  Vec3 offset(double t) const;
  // Target of a vertex whose rest (initial) position is `rest`.
  Vec3 target(const Vec3& rest, double t) const;

  // The knot values the offset is linear in: `offsets` (keyframe offsets or spline points) and
  // `tangents` (Hermite only).
  enum class Control { Offset, Tangent };
  // d offset(t) / d control[knot], the same scalar for each component (the interpolation is
  // componentwise): the linear weights (1 - s, s) of the keyframes, or the Hermite basis
  // h00, h01 (points) and dt h10, dt h11 (tangents) of the interval holding t; outside the key
  // range the held end point has weight 1 and every tangent 0. What the adjoint chains the
  // handle targets through (DiffCloth Appendix B, Hat: the spline's tangents and end point).
  double controlWeight(double t, Control control, int knot) const;

 private:
  struct Segment {
    int first = 0;    // knot at the start of the interval holding t
    double s = 0.0;   // (t - times[first]) / dt, in [0, 1)
    double dt = 0.0;  // interval length; 0 when t is outside the key range (held end point)
  };
  Segment segment(double t) const;
};

}  // namespace weft
