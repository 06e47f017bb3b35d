// The CCD narrow phase (Liang 2019 Sec. 3.3) on configurations with analytic answers: a vertex
// falling through a face, beside it, or coming to rest within the thickness; edges crossing,
// parallel, near-parallel and nearly degenerate. Every impact is checked against Impact.h's
// convention: weights of the closest points, a normal along s(x(t)) or with
// normal . s(start) >= 0, and normal . s(x(t)) equal to the pair's distance at the time of impact.

#include <weft/collision/PairCcd.h>
#include <weft/contact/TriangleBvh.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft::collision {
namespace {

constexpr double kThickness = 1e-3;

PairPositions lerp(const PairPositions& a, const PairPositions& b, double t) {
  PairPositions x;
  for (int k = 0; k < 4; ++k) x[k] = a[k] + t * (b[k] - a[k]);
  return x;
}

Vec3 separation(const Impact& impact, const PairPositions& x) {
  Vec3 s = Vec3::Zero();
  for (int k = 0; k < 4; ++k) s += impact.weights[k] * x[impact.nodes[k]];
  return s;
}

// Distance of the pair at x, computed independently of the impact's weights.
double pairDistance(ImpactKind kind, const PairPositions& x) {
  if (kind == ImpactKind::VertexFace) {
    Vec3 bary;
    TriangleFeature feature;
    return (x[0] - closestPointOnTriangle(x[0], x[1], x[2], x[3], bary, feature)).norm();
  }
  const SegmentClosest c = closestSegmentPoints(x[0], x[1], x[2], x[3]);
  return ((x[0] + c.s * (x[1] - x[0])) - (x[2] + c.u * (x[3] - x[2]))).norm();
}

// The Impact.h convention, for any impact.
void expectConvention(const Impact& impact, const PairPositions& start, const PairPositions& end) {
  EXPECT_NEAR(impact.normal.norm(), 1.0, 1e-12);
  EXPECT_GE(impact.time, 0.0);
  EXPECT_LE(impact.time, 1.0);
  const double sum = impact.weights[0] + impact.weights[1] + impact.weights[2] + impact.weights[3];
  EXPECT_NEAR(sum, 0.0, 1e-12);  // a separation vector: translation invariant
  const PairPositions x = lerp(start, end, impact.time);
  const Vec3 atImpact = separation(impact, x);
  const bool alongSeparation =
      atImpact.norm() > 0.0 && (impact.normal - atImpact.normalized()).norm() < 1e-9;
  if (!alongSeparation) {
    EXPECT_GE(impact.normal.dot(separation(impact, start)), -1e-12);
  }
  EXPECT_NEAR(impact.normal.dot(separation(impact, x)), pairDistance(impact.kind, x), 1e-9);
  for (double w : impact.weights) EXPECT_TRUE(std::isfinite(w));
  EXPECT_TRUE(impact.normal.allFinite());
}

// Triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0, lifted by faceLift at the end.
PairPositions faceWithVertex(const Vec3& vertex, double faceLift = 0.0) {
  const Vec3 up(0, 0, faceLift);
  return {vertex, Vec3(0, 0, 0) + up, Vec3(1, 0, 0) + up, Vec3(0, 1, 0) + up};
}

TEST(CollisionCcd, VertexFallingThroughTheFaceAtTheAnalyticTime) {
  // The vertex falls from z = 1 to z = -1 while the face rises to z = 0.5: they meet when
  // 1 - 2t = 0.5t, at t = 0.4, with the vertex over barycentric (0.5, 0.2, 0.3).
  const PairPositions start = faceWithVertex(Vec3(0.2, 0.3, 1.0));
  const PairPositions end = faceWithVertex(Vec3(0.2, 0.3, -1.0), 0.5);
  const auto impact = vertexFaceCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_EQ(impact->kind, ImpactKind::VertexFace);
  EXPECT_NEAR(impact->time, 0.4, 1e-14);
  EXPECT_NEAR(impact->weights[0], 1.0, 1e-15);
  EXPECT_NEAR(impact->weights[1], -0.5, 1e-12);
  EXPECT_NEAR(impact->weights[2], -0.2, 1e-12);
  EXPECT_NEAR(impact->weights[3], -0.3, 1e-12);
  // The vertex starts above the face: the normal is +z.
  EXPECT_NEAR((impact->normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  expectConvention(*impact, start, end);
  // From below, the normal is -z.
  const auto below = vertexFaceCcd(faceWithVertex(Vec3(0.2, 0.3, -1.0)),
                                   faceWithVertex(Vec3(0.2, 0.3, 1.0)), kThickness);
  ASSERT_TRUE(below);
  EXPECT_NEAR(below->time, 0.5, 1e-14);
  EXPECT_NEAR((below->normal + Vec3::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(CollisionCcd, VertexPassingBesideTheFaceIsNotAnImpact) {
  // Through the plane at (0.6, 0.6), 0.2 / sqrt(2) from the hypotenuse x + y = 1.
  EXPECT_FALSE(vertexFaceCcd(faceWithVertex(Vec3(0.6, 0.6, 1.0)),
                             faceWithVertex(Vec3(0.6, 0.6, -1.0)), kThickness));
  // Beside the face at half the thickness from the edge y = 0: closer than the thickness when
  // coplanar, an impact with the edge's closest point (weights on corners 0 and 1 only).
  const PairPositions start = faceWithVertex(Vec3(0.3, -0.5 * kThickness, 1.0));
  const PairPositions end = faceWithVertex(Vec3(0.3, -0.5 * kThickness, -1.0));
  const auto graze = vertexFaceCcd(start, end, kThickness);
  ASSERT_TRUE(graze);
  EXPECT_NEAR(graze->time, 0.5, 1e-14);
  EXPECT_NEAR(graze->weights[1], -0.7, 1e-12);
  EXPECT_NEAR(graze->weights[2], -0.3, 1e-12);
  EXPECT_EQ(graze->weights[3], 0.0);
  EXPECT_NEAR((graze->normal - Vec3(0, -1, 0)).norm(), 0.0, 1e-9);
  expectConvention(*graze, start, end);
  // Beside at twice the thickness: nothing.
  EXPECT_FALSE(vertexFaceCcd(faceWithVertex(Vec3(0.3, -2 * kThickness, 1.0)),
                             faceWithVertex(Vec3(0.3, -2 * kThickness, -1.0)), kThickness));
}

TEST(CollisionCcd, VertexComingToRestWithinTheThicknessIsReportedAtTimeOne) {
  const PairPositions start = faceWithVertex(Vec3(0.2, 0.3, 0.5));
  const PairPositions end = faceWithVertex(Vec3(0.2, 0.3, 0.4 * kThickness));
  const auto impact = vertexFaceCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_EQ(impact->time, 1.0);
  EXPECT_NEAR((impact->normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(impact->normal.dot(separation(*impact, end)), 0.4 * kThickness, 1e-15);
  expectConvention(*impact, start, end);
  // Stopping at 1.5 thickness: nothing. A pair within the thickness at the start that ends
  // beyond it is not reported either (it needs no response).
  EXPECT_FALSE(vertexFaceCcd(start, faceWithVertex(Vec3(0.2, 0.3, 1.5 * kThickness)), kThickness));
  EXPECT_FALSE(vertexFaceCcd(faceWithVertex(Vec3(0.2, 0.3, 0.5 * kThickness)),
                             faceWithVertex(Vec3(0.2, 0.3, 0.5)), kThickness));
}

TEST(CollisionCcd, VertexHittingAFaceCornerOrEdgeExactly) {
  // Onto corner 2 (0, 1, 0) and onto the hypotenuse's midpoint (0.5, 0.5, 0).
  for (const Vec3& target : {Vec3(0, 1, 0), Vec3(0.5, 0.5, 0)}) {
    const PairPositions start = faceWithVertex(target + Vec3(0.1, -0.2, 0.8));
    const PairPositions end = faceWithVertex(target - 3.0 * Vec3(0.1, -0.2, 0.8));
    const auto impact = vertexFaceCcd(start, end, kThickness);
    ASSERT_TRUE(impact) << target.transpose();
    EXPECT_NEAR(impact->time, 0.25, 1e-12);
    expectConvention(*impact, start, end);
  }
}

TEST(CollisionCcd, VertexMovingInTheFacesPlaneAllStep) {
  // Coplanar for the whole step (Eq. 5 vanishes identically): the vertex slides in the plane
  // z = 0 from (-1, 0.25) into the face, whose edge x = 0 it reaches at t = 1/3.
  const PairPositions start = faceWithVertex(Vec3(-1.0, 0.25, 0.0));
  const PairPositions end = faceWithVertex(Vec3(2.0, 0.25, 0.0));
  const auto impact = vertexFaceCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_NEAR(impact->time, (1.0 - kThickness) / 3.0, 1e-9);
  EXPECT_NEAR((impact->normal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-9);
  expectConvention(*impact, start, end);
}

TEST(CollisionCcd, CoplanarAtRest) {
  // A flat cloth at rest: the vertex 0.5 beside the face, not moving: nothing; the same within
  // half the thickness of the edge x = 0: an impact at time 0.
  const PairPositions apart = faceWithVertex(Vec3(-0.5, 0.25, 0.0));
  EXPECT_FALSE(vertexFaceCcd(apart, apart, kThickness));
  const PairPositions close = faceWithVertex(Vec3(-0.5 * kThickness, 0.25, 0.0));
  const auto impact = vertexFaceCcd(close, close, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_EQ(impact->time, 0.0);
  EXPECT_NEAR((impact->normal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-12);
  expectConvention(*impact, close, close);
}

// Edge a from (-1, 0, 0) to (1, 0, 0) rising by aLift; edge b along y at x = 0.3, height bz.
PairPositions crossingEdges(double bStartZ, double aLift = 0.0) {
  const Vec3 up(0, 0, aLift);
  return {Vec3(-1, 0, 0) + up, Vec3(1, 0, 0) + up, Vec3(0.3, -1, bStartZ), Vec3(0.3, 1, bStartZ)};
}

TEST(CollisionCcd, EdgeMovingThroughAnEdgeAtTheAnalyticTime) {
  // b falls from z = 1 to z = -1 while a rises to 0.5: they meet at t = 0.4, at s = 0.65 on a
  // and u = 0.5 on b; b starts above a, so the normal (along a x b) is -z.
  const PairPositions start = crossingEdges(1.0), end = crossingEdges(-1.0, 0.5);
  const auto impact = edgeEdgeCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_EQ(impact->kind, ImpactKind::EdgeEdge);
  EXPECT_NEAR(impact->time, 0.4, 1e-14);
  EXPECT_NEAR(impact->weights[0], 0.35, 1e-12);
  EXPECT_NEAR(impact->weights[1], 0.65, 1e-12);
  EXPECT_NEAR(impact->weights[2], -0.5, 1e-12);
  EXPECT_NEAR(impact->weights[3], -0.5, 1e-12);
  EXPECT_NEAR((impact->normal + Vec3::UnitZ()).norm(), 0.0, 1e-12);
  expectConvention(*impact, start, end);
  // Passing beyond a's end (b at x = 1.3): no impact.
  PairPositions beyondStart = start, beyondEnd = end;
  for (int k = 2; k < 4; ++k) beyondStart[k].x() = beyondEnd[k].x() = 1.3;
  EXPECT_FALSE(edgeEdgeCcd(beyondStart, beyondEnd, kThickness));
}

TEST(CollisionCcd, PointPassingBesideAVertexIsPushedApartTheWayItLies) {
  // Edge a lies on the x axis; b's end b0 falls through a's height 0.9 mm to its +y side, b
  // pointing away in +y, so the closest point of b is b0 (clamped) and the pair never crosses.
  // At the coplanarity time s = (point on a) - b0 is -y: the normal is -y, the way the pair lies
  // then, although s(start) (b0 0.1 mm to the -y side, 5 mm up) projects onto it negatively.
  // Two edges from b0 give two impacts of the one point pair; with the normal taken from
  // s(start)'s side both would point +y and demand a 2.9 mm sideways move through a.
  const Vec3 from(0, -1e-4, 5e-3), to(0, 1.5e-3, -3e-3);
  for (const Vec3& direction : {Vec3(0.3, 1, 0), Vec3(-0.3, 1, 0)}) {
    const PairPositions start = {Vec3(-1, 0, 0), Vec3(1, 0, 0), from, from + direction};
    const PairPositions end = {Vec3(-1, 0, 0), Vec3(1, 0, 0), to, to + direction};
    const auto impact = edgeEdgeCcd(start, end, 2e-3);
    ASSERT_TRUE(impact);
    EXPECT_NEAR(impact->time, 5.0 / 8.0, 1e-12);
    EXPECT_NEAR(impact->weights[2], -1.0, 1e-12);  // b0, clamped
    EXPECT_NEAR((impact->normal + Vec3::UnitY()).norm(), 0.0, 1e-9);
    expectConvention(*impact, start, end);
  }
}

TEST(CollisionCcd, ParallelEdges) {
  // Parallel edges are always coplanar. b slides in the plane z = 0 from y = 0.5 to y = -0.5
  // across a: within the thickness from t = 0.5 - thickness.
  const PairPositions start = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 0.5, 0), Vec3(1.2, 0.5, 0)};
  const PairPositions end = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, -0.5, 0), Vec3(1.2, -0.5, 0)};
  const auto impact = edgeEdgeCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_NEAR(impact->time, 0.5 - kThickness, 1e-9);
  EXPECT_NEAR((impact->normal - Vec3(0, -1, 0)).norm(), 0.0, 1e-9);
  expectConvention(*impact, start, end);
  // Parallel and side by side at 2 thickness: nothing; coming to rest at 0.5 thickness: within
  // the thickness from 0.5 - t (0.5 - 0.5 thickness) = thickness on.
  PairPositions apart = start;
  for (int k = 2; k < 4; ++k) apart[k].y() = 2 * kThickness;
  EXPECT_FALSE(edgeEdgeCcd(apart, apart, kThickness));
  PairPositions rest = start;
  for (int k = 2; k < 4; ++k) rest[k].y() = 0.5 * kThickness;
  const auto resting = edgeEdgeCcd(start, rest, kThickness);
  ASSERT_TRUE(resting);
  EXPECT_NEAR(resting->time, (0.5 - kThickness) / (0.5 - 0.5 * kThickness), 1e-9);
  expectConvention(*resting, start, rest);
}

TEST(CollisionCcd, NearParallelEdgesWithoutNaN) {
  // b nearly parallel to a (angle 1e-8), falling onto it from z = 1 to z = -1: they are
  // coplanar (and touching) at t = 0.5.
  const Vec3 bEnd(1.0, 1e-8, 0.0);
  const PairPositions start = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), bEnd + Vec3(0, 0, 1)};
  const PairPositions end = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), bEnd - Vec3(0, 0, 1)};
  const auto impact = edgeEdgeCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_NEAR(impact->time, 0.5, 1e-7);
  EXPECT_NEAR((impact->normal + Vec3::UnitZ()).norm(), 0.0, 1e-6);  // b comes from above
  expectConvention(*impact, start, end);
  // The same pair passing 1 m to the side: nothing.
  PairPositions aside = start, asideEnd = end;
  for (int k = 2; k < 4; ++k) aside[k].y() += 1.0, asideEnd[k].y() += 1.0;
  EXPECT_FALSE(edgeEdgeCcd(aside, asideEnd, kThickness));
}

TEST(CollisionCcd, NearlyDegenerateEdgesWithoutNaN) {
  // a is 1e-9 long; b falls through it from z = 1 to z = -1.
  const PairPositions start = {Vec3(0, 0, 0), Vec3(1e-9, 0, 0), Vec3(5e-10, -1, 1),
                               Vec3(5e-10, 1, 1)};
  const PairPositions end = {Vec3(0, 0, 0), Vec3(1e-9, 0, 0), Vec3(5e-10, -1, -1),
                             Vec3(5e-10, 1, -1)};
  const auto impact = edgeEdgeCcd(start, end, kThickness);
  ASSERT_TRUE(impact);
  EXPECT_NEAR(impact->time, 0.5, 1e-6);
  expectConvention(*impact, start, end);
  // A zero-length edge (a point) and a zero-area face: finite results too.
  PairPositions point = start, pointEnd = end;
  point[1] = point[0], pointEnd[1] = pointEnd[0];
  const auto pointImpact = edgeEdgeCcd(point, pointEnd, kThickness);
  ASSERT_TRUE(pointImpact);
  expectConvention(*pointImpact, point, pointEnd);
  const PairPositions flatStart = {Vec3(0.5, 0, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  const PairPositions flatEnd = {Vec3(0.5, 0, -1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  const auto flat = vertexFaceCcd(flatStart, flatEnd, kThickness);
  ASSERT_TRUE(flat);
  EXPECT_TRUE(flat->normal.allFinite());
  for (double w : flat->weights) EXPECT_TRUE(std::isfinite(w));
}

}  // namespace
}  // namespace weft::collision
