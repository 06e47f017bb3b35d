#pragma once
// Narrow phase of continuous collision detection (Liang et al. 2019 Sec. 3.3, after Bridson et
// al. 2002 and ARCSim): for one vertex-face or edge-edge pair of points moving linearly over a
// step, the earliest time in [0, 1] at which the four points are coplanar (Liang Eq. 5) and the
// pair is then closer than the thickness; failing that, whether the pair ends the step closer
// than the thickness (the impact-zone solve constrains those too, reported at time 1). A pair
// that comes within the thickness during the step without ever being coplanar, and ends beyond
// it, crossed nothing and is not an impact. When Eq. 5 vanishes identically (the four points
// coplanar all step) the earliest time within the thickness is found by conservative advancement.
//
// Distances are to the closest points: of the triangle (barycentrics clamped to it, so a vertex
// crossing the plane just outside an edge but within the thickness is an impact whose weights
// sit on that edge's corners), and of the two segments (parameters clamped to [0, 1]).
//
// Nodes are local (0..3): vertex-face {vertex, face corner 0, 1, 2}, edge-edge {a0, a1, b0, b1};
// the caller maps them to mesh indices. The Impact follows collision/Impact.h: weights from the
// closest points at the time of impact, normal the unit separation direction then (the face
// normal, or the edges' common perpendicular, when the closest points are interior). A
// separation normal, s(x(t)) / |s(x(t))|, keeps its direction; the others are oriented so that
// normal . s(start) >= 0 (against the approach, normal . (s(end) - s(start)) <= 0, when
// normal . s(start) vanishes: a pair coplanar at the start).
//
// Derivatives (Liang Eq. 6-7, with the sign of Eq. 7 fixed as in notes/algorithms.md Sec. 4):
// the time of impact and the impact's normal and weights with respect to the 24 coordinates
// (start positions of nodes 0..3, x y z each, then end positions), at fixed pair topology.

#include <weft/collision/Impact.h>

#include <array>
#include <optional>

namespace weft::collision {

using PairPositions = std::array<Vec3, 4>;
using PairGradient = Eigen::Matrix<double, 1, 24>;

// Real roots of a t^3 + b t^2 + c t + d in [lo, hi], ascending and distinct. The interval is
// split at the cubic's critical points into monotone pieces; each sign change is bracketed and
// refined by safeguarded Newton; a piece endpoint where |f| <= tolerance times the bound
// |a| m^3 + |b| m^2 + |c| m + |d| (m = max(1, |lo|, |hi|)) counts as a root, which catches
// double roots (and merges roots closer than about sqrt(tolerance)). Lower degrees (a or b
// vanishing) need no special case: the critical points come from a stable quadratic formula.
struct CubicRoots {
  int count = 0;
  std::array<double, 4> t{{0.0, 0.0, 0.0, 0.0}};
  bool identicallyZero = false;  // all coefficients zero: every t is a root
};
CubicRoots solveCubic(double a, double b, double c, double d, double lo = 0.0, double hi = 1.0,
                      double tolerance = 1e-12);

// Coefficients {a, b, c, d} of Liang Eq. 5: (x1 + t v1) . (x2 + t v2) x (x3 + t v3), with x_k
// and v_k the start position and displacement of node k relative to node 0.
std::array<double, 4> coplanarityCubic(const PairPositions& start, const PairPositions& end);

std::optional<Impact> vertexFaceCcd(const PairPositions& start, const PairPositions& end,
                                    double thickness);
std::optional<Impact> edgeEdgeCcd(const PairPositions& start, const PairPositions& end,
                                  double thickness);
// Either of the two by kind.
std::optional<Impact> pairCcd(ImpactKind kind, const PairPositions& start, const PairPositions& end,
                              double thickness);

// How an impact's time was found: it decides which quantities vary with the coordinates.
enum class ImpactTimeSource : int {
  CoplanarityRoot = 0,  // a root of Liang Eq. 5: t varies (timeOfImpactGradient)
  EndProximity = 1,     // closer than the thickness at the end of the step: t = 1 fixed
  CoplanarSweep = 2,    // coplanar all step: t by conservative advancement, held fixed
};

// d t / d (start, end) at a simple root t of Liang Eq. 5, by implicit differentiation:
// dt = -(t^3 da + t^2 db + t dc + dd) / (3 a t^2 + 2 b t + c).
PairGradient timeOfImpactGradient(const PairPositions& start, const PairPositions& end, double t);

// Jacobians of the impact found by pairCcd (kind, start, end, thickness) with respect to the 24
// coordinates, holding its topology fixed: the closest features (face interior, an edge or a
// corner of the face; interior or clamped edge parameters), the orientation sign and the time
// source. Forward-mode automatic differentiation of the closest-point code evaluated at
// x(t) = start + t (end - start), t itself differentiated for a coplanarity root.
struct ImpactJacobian {
  Impact impact;
  ImpactTimeSource source = ImpactTimeSource::CoplanarityRoot;
  PairGradient time = PairGradient::Zero();
  Eigen::Matrix<double, 3, 24> normal = Eigen::Matrix<double, 3, 24>::Zero();
  Eigen::Matrix<double, 4, 24> weights = Eigen::Matrix<double, 4, 24>::Zero();
};
std::optional<ImpactJacobian> impactJacobian(ImpactKind kind, const PairPositions& start,
                                             const PairPositions& end, double thickness);

// Closest points of segments [p0, p1] and [q0, q1]: parameters s (on p) and u (on q) in [0, 1].
// Parallel or degenerate segments get a valid (not unique) pair. sFree/uFree say whether the
// parameter lies strictly inside (0, 1) and was not clamped.
struct SegmentClosest {
  double s = 0.0, u = 0.0;
  bool sFree = false, uFree = false;
};
SegmentClosest closestSegmentPoints(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace weft::collision
