#include <weft/collision/PairCcd.h>

#include <weft/contact/TriangleBvh.h>

#include <unsupported/Eigen/AutoDiff>

#include <algorithm>
#include <cmath>

namespace weft::collision {
namespace {

// --- Small templated vector algebra: the same code runs on double and on forward-mode
// derivatives (Eigen's AutoDiffScalar), so the Jacobians differentiate exactly what the
// detection evaluates.
template <typename S>
struct V {
  S x, y, z;
};
template <typename S>
V<S> operator+(const V<S>& a, const V<S>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename S>
V<S> operator-(const V<S>& a, const V<S>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename S, typename T>
V<S> operator*(const T& k, const V<S>& a) {
  return {k * a.x, k * a.y, k * a.z};
}
template <typename S>
S dot(const V<S>& a, const V<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename S>
V<S> cross(const V<S>& a, const V<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename S>
V<S> normalized(const V<S>& a) {
  using std::sqrt;
  const S n = sqrt(dot(a, a));
  return {a.x / n, a.y / n, a.z / n};
}
V<double> toV(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}
Vec3 toVec3(const V<double>& v) {
  return Vec3(v.x, v.y, v.z);
}

template <typename S>
using Nodes = std::array<V<S>, 4>;

// Liang Eq. 5 expanded in powers of t; x_k, v_k relative to node 0.
template <typename S>
std::array<S, 4> cubicCoefficients(const Nodes<S>& start, const Nodes<S>& end) {
  V<S> x[3], v[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = start[k + 1] - start[0];
    v[k] = (end[k + 1] - end[0]) - x[k];
  }
  const V<S> x23 = cross(x[1], x[2]), v23 = cross(v[1], v[2]);
  const V<S> mixed = cross(x[1], v[2]) + cross(v[1], x[2]);
  return {dot(v[0], v23), dot(x[0], v23) + dot(v[0], mixed), dot(x[0], mixed) + dot(v[0], x23),
          dot(x[0], x23)};
}

template <typename S, typename T>
Nodes<S> positionsAt(const Nodes<S>& start, const Nodes<S>& end, const T& t) {
  Nodes<S> x;
  for (int k = 0; k < 4; ++k) x[k] = start[k] + t * (end[k] - start[k]);
  return x;
}

Nodes<double> toNodes(const PairPositions& p) {
  return {toV(p[0]), toV(p[1]), toV(p[2]), toV(p[3])};
}

// Which closed form the normal follows; held fixed when differentiating.
enum class NormalMode : int {
  FaceNormal,  // vertex-face, closest point in the face interior: the face's unit normal
  EdgeCross,   // edge-edge, both closest points interior: the edges' common perpendicular
  Separation,  // otherwise s(x(t)) / |s(x(t))|
  Approach,    // s(x(t)) vanishes: -(s(end) - s(start)) normalized, the direction of approach
  Constant,    // nothing better defined (a fully degenerate pair): a fixed direction
};

// The pair's closest points at one time, from double positions.
struct Evaluation {
  std::array<double, 4> w{{0, 0, 0, 0}};
  double distance = 0.0;
  TriangleFeature feature = TriangleFeature::Face;
  SegmentClosest segment;
};

Evaluation evaluate(ImpactKind kind, const Nodes<double>& x) {
  Evaluation e;
  if (kind == ImpactKind::VertexFace) {
    Vec3 bary;
    const Vec3 p = toVec3(x[0]);
    const Vec3 q =
        closestPointOnTriangle(p, toVec3(x[1]), toVec3(x[2]), toVec3(x[3]), bary, e.feature);
    e.w = {1.0, -bary[0], -bary[1], -bary[2]};
    e.distance = (p - q).norm();
  } else {
    e.segment = closestSegmentPoints(toVec3(x[0]), toVec3(x[1]), toVec3(x[2]), toVec3(x[3]));
    const double s = e.segment.s, u = e.segment.u;
    e.w = {1.0 - s, s, -(1.0 - u), -u};
    V<double> sep{0, 0, 0};
    for (int k = 0; k < 4; ++k) sep = sep + e.w[k] * x[k];
    e.distance = std::sqrt(dot(sep, sep));
  }
  return e;
}

// Separation weights at fixed topology (the feature of a vertex-face pair, which edge
// parameters are free for an edge-edge pair), as a function of the positions x.
template <typename S>
std::array<S, 4> weightsAt(ImpactKind kind, const Evaluation& e, const Nodes<S>& x) {
  if (kind == ImpactKind::VertexFace) {
    const V<S> ab = x[2] - x[1], ac = x[3] - x[1], ap = x[0] - x[1];
    S b0, b1, b2;
    switch (e.feature) {
      case TriangleFeature::Face: {
        const S d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac);
        const S d20 = dot(ap, ab), d21 = dot(ap, ac);
        const S den = d00 * d11 - d01 * d01;
        b1 = (d11 * d20 - d01 * d21) / den;
        b2 = (d00 * d21 - d01 * d20) / den;
        b0 = S(1.0) - b1 - b2;
        break;
      }
      case TriangleFeature::Edge01:
        b1 = dot(ap, ab) / dot(ab, ab), b0 = S(1.0) - b1, b2 = S(0.0);
        break;
      case TriangleFeature::Edge20:
        b2 = dot(ap, ac) / dot(ac, ac), b0 = S(1.0) - b2, b1 = S(0.0);
        break;
      case TriangleFeature::Edge12: {
        const V<S> bc = x[3] - x[2];
        b2 = dot(x[0] - x[2], bc) / dot(bc, bc), b1 = S(1.0) - b2, b0 = S(0.0);
        break;
      }
      default:  // a corner: constant weights
        b0 = S(-e.w[1]), b1 = S(-e.w[2]), b2 = S(-e.w[3]);
    }
    return {S(1.0), -b0, -b1, -b2};
  }
  const V<S> d1 = x[1] - x[0], d2 = x[3] - x[2], r = x[0] - x[2];
  S s(e.segment.s), u(e.segment.u);
  if (e.segment.sFree && e.segment.uFree) {
    const S a = dot(d1, d1), b = dot(d1, d2), c = dot(d1, r), ee = dot(d2, d2), f = dot(d2, r);
    const S den = a * ee - b * b;
    s = (b * f - c * ee) / den;
    u = (a * f - b * c) / den;
  } else if (e.segment.uFree) {
    u = dot(x[0] + s * d1 - x[2], d2) / dot(d2, d2);
  } else if (e.segment.sFree) {
    s = dot(x[2] + u * d2 - x[0], d1) / dot(d1, d1);
  }
  return {S(1.0) - s, s, -(S(1.0) - u), -u};
}

template <typename S>
V<S> separation(const std::array<S, 4>& w, const Nodes<S>& x) {
  V<S> sep = w[0] * x[0];
  for (int k = 1; k < 4; ++k) sep = sep + w[k] * x[k];
  return sep;
}

// Unit normal (before orientation) for a mode.
template <typename S>
V<S> normalFor(NormalMode mode, const std::array<S, 4>& w, const Nodes<S>& x, const Nodes<S>& start,
               const Nodes<S>& end, const Vec3& constant) {
  switch (mode) {
    case NormalMode::FaceNormal:
      return normalized(cross(x[2] - x[1], x[3] - x[1]));
    case NormalMode::EdgeCross:
      return normalized(cross(x[1] - x[0], x[3] - x[2]));
    case NormalMode::Separation:
      return normalized(separation(w, x));
    case NormalMode::Approach:
      return normalized(separation(w, start) - separation(w, end));
    default:
      return {S(constant.x()), S(constant.y()), S(constant.z())};
  }
}

// Everything detection decides, so that differentiation can hold it fixed.
struct Detection {
  Impact impact;
  ImpactTimeSource source = ImpactTimeSource::CoplanarityRoot;
  Evaluation evaluation;
  NormalMode mode = NormalMode::Constant;
  Vec3 constantNormal = Vec3::UnitZ();
  double sign = 1.0;
};

double characteristicLength(const Nodes<double>& start, const Nodes<double>& end) {
  double l2 = 0.0;
  for (int k = 0; k < 4; ++k) {
    const V<double> a = start[k] - start[0], b = end[k] - end[0], m = end[k] - start[k];
    l2 = std::max({l2, dot(a, a), dot(b, b), dot(m, m)});
  }
  return std::sqrt(l2);
}

Detection finish(ImpactKind kind, const Nodes<double>& start, const Nodes<double>& end, double t,
                 const Evaluation& e, ImpactTimeSource source, double length) {
  Detection d;
  d.source = source;
  d.evaluation = e;
  const Nodes<double> x = positionsAt(start, end, t);
  const double tiny = 1e-12 * length;
  const V<double> sepT = separation(e.w, x);
  const V<double> approach = separation(e.w, start) - separation(e.w, end);
  const V<double> faceCross = cross(x[2] - x[1], x[3] - x[1]);
  const V<double> edgeCross = cross(x[1] - x[0], x[3] - x[2]);
  if (kind == ImpactKind::VertexFace && e.feature == TriangleFeature::Face &&
      dot(faceCross, faceCross) > 0.0)
    d.mode = NormalMode::FaceNormal;
  else if (kind == ImpactKind::EdgeEdge && e.segment.sFree && e.segment.uFree)
    d.mode = NormalMode::EdgeCross;  // closestSegmentPoints frees both only when not parallel
  else if (std::sqrt(dot(sepT, sepT)) > tiny)
    d.mode = NormalMode::Separation;
  else if (std::sqrt(dot(approach, approach)) > tiny)
    d.mode = NormalMode::Approach;
  else {
    d.mode = NormalMode::Constant;
    const V<double> c = kind == ImpactKind::VertexFace ? faceCross : edgeCross;
    if (dot(c, c) > 0.0) d.constantNormal = toVec3(normalized(c));
  }
  V<double> n = normalFor(d.mode, e.w, x, start, end, d.constantNormal);
  // Orientation. A separation normal is the pair's own direction at the time of impact and keeps
  // it: the pair is pushed apart the way it lies then. Oriented by s(start) instead, a point
  // passing beside a vertex (sideways at the impact, having come along s(start)) gets a sign
  // decided by a nearly perpendicular projection, and two impacts of one point pair (found
  // through two edges sharing the vertex) can get opposite normals whose constraints together
  // push the pair far apart. The other normals (face, edge cross product: s(x(t)) vanishes along
  // them) take the side the pair started on, normal . s(start) >= 0, and a pair coplanar at the
  // start is oriented against its approach, normal . (s(end) - s(start)) <= 0 (as ARCSim does).
  const double atStart = dot(n, separation(e.w, start));
  if (d.mode == NormalMode::Separation)
    d.sign = 1.0;
  else if (std::abs(atStart) > tiny)
    d.sign = atStart > 0.0 ? 1.0 : -1.0;
  else
    d.sign = dot(n, approach) >= 0.0 ? 1.0 : -1.0;
  n = d.sign * n;
  d.impact.kind = kind;
  d.impact.nodes = {0, 1, 2, 3};
  d.impact.weights = e.w;
  d.impact.normal = toVec3(n);
  d.impact.time = t;
  return d;
}

std::optional<Detection> detect(ImpactKind kind, const PairPositions& startIn,
                                const PairPositions& endIn, double thickness) {
  const Nodes<double> start = toNodes(startIn), end = toNodes(endIn);
  const double length = characteristicLength(start, end);
  const std::array<double, 4> k = cubicCoefficients(start, end);
  const double magnitude = std::abs(k[0]) + std::abs(k[1]) + std::abs(k[2]) + std::abs(k[3]);
  // The cubic is of the order length^3; below this it is rounding noise: the four points stay
  // coplanar all step and Eq. 5 says nothing about when they meet.
  const bool coplanarAllStep = !(magnitude > 1e-13 * length * length * length);
  if (!coplanarAllStep) {
    const CubicRoots roots = solveCubic(k[0], k[1], k[2], k[3]);
    for (int i = 0; i < roots.count; ++i) {
      const double t = roots.t[i];
      const Evaluation e = evaluate(kind, positionsAt(start, end, t));
      if (e.distance < thickness)
        return finish(kind, start, end, t, e, ImpactTimeSource::CoplanarityRoot, length);
    }
  } else {
    // Coplanar all step: the earliest time closer than the thickness by conservative
    // advancement. The distance changes at most at the rate `speed` (the largest relative
    // displacement of a node of one primitive to a node of the other), so from a time at
    // distance d it cannot reach the thickness before (d - thickness) / speed later. Steps are at
    // least kMinStep, so a dip below the thickness shorter than that, at most speed * kMinStep / 2
    // deep, can be stepped over; the first step that lands within is refined by bisection.
    constexpr double kMinStep = 1.0 / 4096;
    const int firstOther = kind == ImpactKind::VertexFace ? 1 : 2;
    double speed = 0.0;
    for (int i = 0; i < firstOther; ++i)
      for (int j = firstOther; j < 4; ++j) {
        const V<double> relative = (end[i] - start[i]) - (end[j] - start[j]);
        speed = std::max(speed, std::sqrt(dot(relative, relative)));
      }
    double t = 0.0, distance = evaluate(kind, start).distance;
    if (distance < thickness)
      return finish(kind, start, end, 0.0, evaluate(kind, start), ImpactTimeSource::CoplanarSweep,
                    length);
    while (speed > 0.0 && t < 1.0) {
      const double next = std::min(1.0, t + std::max((distance - thickness) / speed, kMinStep));
      const double nextDistance = evaluate(kind, positionsAt(start, end, next)).distance;
      if (nextDistance < thickness) {
        double lo = t, hi = next;
        for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
          const double mid = 0.5 * (lo + hi);
          (evaluate(kind, positionsAt(start, end, mid)).distance < thickness ? hi : lo) = mid;
        }
        if (hi >= 1.0) break;  // reported below as proximity at the end of the step
        return finish(kind, start, end, hi, evaluate(kind, positionsAt(start, end, hi)),
                      ImpactTimeSource::CoplanarSweep, length);
      }
      t = next, distance = nextDistance;
    }
  }
  const Evaluation atEnd = evaluate(kind, end);
  if (atEnd.distance < thickness)
    return finish(kind, start, end, 1.0, atEnd, ImpactTimeSource::EndProximity, length);
  return std::nullopt;
}

double cubicAt(double a, double b, double c, double d, double t) {
  return ((a * t + b) * t + c) * t + d;
}

using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;

// Start (derivative index 3k + j) and end (12 + 3k + j) coordinates as active variables.
void activeNodes(const PairPositions& start, const PairPositions& end, Nodes<AD>& s, Nodes<AD>& e) {
  for (int k = 0; k < 4; ++k) {
    s[k] = {AD(start[k].x(), 24, 3 * k), AD(start[k].y(), 24, 3 * k + 1),
            AD(start[k].z(), 24, 3 * k + 2)};
    e[k] = {AD(end[k].x(), 24, 12 + 3 * k), AD(end[k].y(), 24, 12 + 3 * k + 1),
            AD(end[k].z(), 24, 12 + 3 * k + 2)};
  }
}

}  // namespace

CubicRoots solveCubic(double a, double b, double c, double d, double lo, double hi,
                      double tolerance) {
  CubicRoots roots;
  const double magnitude = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
  if (magnitude == 0.0) {
    roots.identicallyZero = true;
    return roots;
  }
  a /= magnitude, b /= magnitude, c /= magnitude, d /= magnitude;
  const double m = std::max({1.0, std::abs(lo), std::abs(hi)});
  const double eps =
      tolerance * (std::abs(a) * m * m * m + std::abs(b) * m * m + std::abs(c) * m + std::abs(d));
  auto f = [&](double t) { return cubicAt(a, b, c, d, t); };
  auto df = [&](double t) { return (3.0 * a * t + 2.0 * b) * t + c; };

  // Critical points 3a t^2 + 2b t + c = 0 (stable form: no cancellation when a is tiny).
  std::array<double, 4> breaks;
  int nb = 0;
  breaks[nb++] = lo;
  const double qa = 3.0 * a, qb = 2.0 * b, qc = c;
  std::array<double, 2> crit;
  int nc = 0;
  if (qa == 0.0) {
    if (qb != 0.0) crit[nc++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      if (q != 0.0) {
        crit[nc++] = q / qa;
        crit[nc++] = qc / q;
      } else {
        crit[nc++] = 0.0;
      }
    }
  }
  std::sort(crit.begin(), crit.begin() + nc);
  for (int i = 0; i < nc; ++i)
    if (crit[i] > lo && crit[i] < hi) breaks[nb++] = crit[i];
  breaks[nb++] = hi;

  auto add = [&](double t) {
    if (roots.count > 0 && t - roots.t[roots.count - 1] <= 1e-14 * m) return;
    roots.t[roots.count++] = t;
  };
  for (int i = 0; i + 1 < nb; ++i) {
    double l = breaks[i], r = breaks[i + 1];
    double fl = f(l);
    const double fr = f(r);
    if (std::abs(fl) <= eps) {  // touching (a double root at a critical point) or an exact root
      add(l);
      continue;
    }
    if (std::abs(fr) <= eps || (fl > 0.0) == (fr > 0.0)) continue;
    // Monotone with a sign change: safeguarded Newton inside the bracket.
    double t = 0.5 * (l + r);
    for (int it = 0; it < 100; ++it) {
      const double ft = f(t);
      if (ft == 0.0) break;
      if ((ft > 0.0) == (fl > 0.0))
        l = t, fl = ft;
      else
        r = t;
      double next = t - ft / df(t);
      if (!(next > l && next < r)) next = 0.5 * (l + r);
      const bool converged = std::abs(next - t) <= 1e-16 * m || r - l <= 1e-16 * m;
      t = next;
      if (converged) break;
    }
    add(t);
  }
  if (std::abs(f(hi)) <= eps) add(hi);
  return roots;
}

std::array<double, 4> coplanarityCubic(const PairPositions& start, const PairPositions& end) {
  return cubicCoefficients(toNodes(start), toNodes(end));
}

SegmentClosest closestSegmentPoints(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                    const Vec3& q1) {
  // Minimise |p0 + s d1 - q0 - u d2|^2 over the unit square: the interior stationary point when
  // the segments are not parallel, else clamp one parameter and project for the other.
  SegmentClosest out;
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
  double s = 0.0, u = 0.0;
  const bool pPoint = !(a > 0.0), qPoint = !(e > 0.0);
  if (pPoint && qPoint) {
    s = u = 0.0;
  } else if (pPoint) {
    u = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (qPoint) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2), den = a * e - b * b;
      // Parallel (sin^2 of the angle below 1e-12): any s works; s = 0 then u by projection.
      const bool parallel = !(den > 1e-12 * a * e);
      s = parallel ? 0.0 : clamp01((b * f - c * e) / den);
      u = (b * s + f) / e;
      if (u < 0.0)
        u = 0.0, s = clamp01(-c / a);
      else if (u > 1.0)
        u = 1.0, s = clamp01((b - c) / a);
      out.sFree = !parallel && s > 0.0 && s < 1.0;
      out.uFree = u > 0.0 && u < 1.0;
      // A parallel pair keeps s held (s = 0 or clamped) so only u is free.
      if (parallel && s > 0.0 && s < 1.0 && !out.uFree) out.sFree = true;
      out.s = s, out.u = u;
      return out;
    }
  }
  out.s = s, out.u = u;
  out.sFree = !pPoint && s > 0.0 && s < 1.0;
  out.uFree = !qPoint && u > 0.0 && u < 1.0;
  return out;
}

std::optional<Impact> vertexFaceCcd(const PairPositions& start, const PairPositions& end,
                                    double thickness) {
  const auto d = detect(ImpactKind::VertexFace, start, end, thickness);
  if (!d) return std::nullopt;
  return d->impact;
}

std::optional<Impact> edgeEdgeCcd(const PairPositions& start, const PairPositions& end,
                                  double thickness) {
  const auto d = detect(ImpactKind::EdgeEdge, start, end, thickness);
  if (!d) return std::nullopt;
  return d->impact;
}

std::optional<Impact> pairCcd(ImpactKind kind, const PairPositions& start, const PairPositions& end,
                              double thickness) {
  return kind == ImpactKind::VertexFace ? vertexFaceCcd(start, end, thickness)
                                        : edgeEdgeCcd(start, end, thickness);
}

PairGradient timeOfImpactGradient(const PairPositions& start, const PairPositions& end, double t) {
  Nodes<AD> s, e;
  activeNodes(start, end, s, e);
  const std::array<AD, 4> k = cubicCoefficients(s, e);
  const double slope = (3.0 * k[0].value() * t + 2.0 * k[1].value()) * t + k[2].value();
  const Eigen::Matrix<double, 24, 1> dcubic = t * t * t * k[0].derivatives() +
                                              t * t * k[1].derivatives() + t * k[2].derivatives() +
                                              k[3].derivatives();
  return (-dcubic / slope).transpose();
}

std::optional<ImpactJacobian> impactJacobian(ImpactKind kind, const PairPositions& start,
                                             const PairPositions& end, double thickness) {
  const auto d = detect(kind, start, end, thickness);
  if (!d) return std::nullopt;
  ImpactJacobian out;
  out.impact = d->impact;
  out.source = d->source;
  const double t = d->impact.time;
  if (d->source == ImpactTimeSource::CoplanarityRoot)
    out.time = timeOfImpactGradient(start, end, t);
  Nodes<AD> s, e;
  activeNodes(start, end, s, e);
  const Eigen::Matrix<double, 24, 1> dt = out.time.transpose();
  const AD tAD(t, dt);
  const Nodes<AD> x = positionsAt(s, e, tAD);
  const std::array<AD, 4> w = weightsAt(kind, d->evaluation, x);
  const V<AD> n = normalFor(d->mode, w, x, s, e, d->constantNormal);
  for (int k = 0; k < 4; ++k) out.weights.row(k) = w[k].derivatives().transpose();
  out.normal.row(0) = d->sign * n.x.derivatives().transpose();
  out.normal.row(1) = d->sign * n.y.derivatives().transpose();
  out.normal.row(2) = d->sign * n.z.derivatives().transpose();
  return out;
}

}  // namespace weft::collision
