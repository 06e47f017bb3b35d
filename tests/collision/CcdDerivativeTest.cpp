// Derivatives of continuous collision detection (Liang 2019 Eq. 6-7, with the sign fixed as in
// notes/algorithms.md Sec. 4): the time of impact and the impact's normal and weights with
// respect to the 12 start and 12 end coordinates, against central finite differences of the
// detection itself, on random configurations away from degeneracies: vertex-face and edge-edge
// impacts at a coplanarity root (t varies), at the end of the step (t = 1 fixed), and a
// vertex-face impact whose closest point is on an edge of the face (normal along the separation).

#include <weft/collision/PairCcd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <random>

namespace weft::collision {
namespace {

using Coords = Eigen::Matrix<double, 24, 1>;
using Values = Eigen::Matrix<double, 8, 1>;  // time, normal (3), weights (4)

Coords pack(const PairPositions& start, const PairPositions& end) {
  Coords x;
  for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) = start[k], x.segment<3>(12 + 3 * k) = end[k];
  return x;
}

void unpack(const Coords& x, PairPositions& start, PairPositions& end) {
  for (int k = 0; k < 4; ++k) start[k] = x.segment<3>(3 * k), end[k] = x.segment<3>(12 + 3 * k);
}

// The detected impact as a vector; false when there is none or it was found differently.
bool detectValues(ImpactKind kind, const Coords& x, double thickness, ImpactTimeSource source,
                  Values& out) {
  PairPositions start, end;
  unpack(x, start, end);
  const auto j = impactJacobian(kind, start, end, thickness);
  if (!j || j->source != source) return false;
  out << j->impact.time, j->impact.normal, j->impact.weights[0], j->impact.weights[1],
      j->impact.weights[2], j->impact.weights[3];
  return true;
}

double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-12);
}

struct Outcome {
  int checked = 0;
  double worstTime = 0.0, worstJacobian = 0.0;
};

// Compares impactJacobian with central differences (step h) at x; skips configurations whose
// impact changes source or topology within the step (the weights' zero pattern).
void check(ImpactKind kind, const Coords& x, double thickness, ImpactTimeSource source,
           Outcome& outcome, double h = 1e-6) {
  PairPositions start, end;
  unpack(x, start, end);
  const auto j = impactJacobian(kind, start, end, thickness);
  if (!j || j->source != source) return;
  Eigen::Matrix<double, 8, 24> fd;
  for (int i = 0; i < 24; ++i) {
    Values plus, minus;
    Coords xp = x, xm = x;
    xp[i] += h, xm[i] -= h;
    if (!detectValues(kind, xp, thickness, source, plus) ||
        !detectValues(kind, xm, thickness, source, minus))
      return;
    for (int k = 0; k < 4; ++k)
      if ((plus[4 + k] == 0.0) != (j->impact.weights[k] == 0.0) ||
          (minus[4 + k] == 0.0) != (j->impact.weights[k] == 0.0))
        return;
    fd.col(i) = (plus - minus) / (2 * h);
  }
  Eigen::Matrix<double, 8, 24> analytic;
  analytic.row(0) = j->time;
  analytic.middleRows<3>(1) = j->normal;
  analytic.middleRows<4>(4) = j->weights;
  const double timeError = relativeError(fd.row(0), analytic.row(0));
  const double jacobianError = relativeError(fd.bottomRows<7>(), analytic.bottomRows<7>());
  if (source == ImpactTimeSource::CoplanarityRoot) {
    EXPECT_LT(timeError, 1e-6);
    EXPECT_GT(analytic.row(0).norm(), 1e-3);  // the time does move with the coordinates
    // timeOfImpactGradient is the same derivative.
    EXPECT_LT(relativeError(timeOfImpactGradient(start, end, j->impact.time), fd.row(0)), 1e-6);
  } else {
    EXPECT_EQ(analytic.row(0).norm(), 0.0);
    EXPECT_EQ(fd.row(0).norm(), 0.0);
  }
  EXPECT_LT(jacobianError, 1e-6);
  EXPECT_GT(analytic.bottomRows<7>().norm(), 1e-3);
  outcome.checked++;
  outcome.worstTime = std::max(outcome.worstTime, timeError);
  outcome.worstJacobian = std::max(outcome.worstJacobian, jacobianError);
}

Vec3 randomVec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

// A pair meeting at time tMeet: nodes 1..3 (face) or 2..3 (edge b) and the first node(s) move
// freely; the remaining node is placed so the pair touches at tMeet at the given parameters.
Coords randomVertexFaceCrossing(std::mt19937& rng, double tMeet, const Vec3& bary,
                                const Vec3& offsetAtMeet) {
  PairPositions start, end;
  for (int k = 1; k < 4; ++k) {
    start[k] = randomVec(rng, 1.0);
    end[k] = start[k] + randomVec(rng, 0.3);
  }
  Vec3 meet = offsetAtMeet;
  for (int k = 1; k < 4; ++k) meet += bary[k - 1] * (start[k] + tMeet * (end[k] - start[k]));
  const Vec3 v = randomVec(rng, 1.0);
  start[0] = meet - tMeet * v, end[0] = meet + (1 - tMeet) * v;
  return pack(start, end);
}

TEST(CollisionCcdDerivatives, VertexFaceAtACoplanarityRoot) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Outcome outcome;
  for (int trial = 0; trial < 60; ++trial) {
    const double b1 = 0.15 + 0.35 * u(rng), b2 = 0.15 + 0.35 * u(rng);
    const Coords x =
        randomVertexFaceCrossing(rng, 0.2 + 0.6 * u(rng), Vec3(1 - b1 - b2, b1, b2), Vec3::Zero());
    check(ImpactKind::VertexFace, x, 1e-3, ImpactTimeSource::CoplanarityRoot, outcome);
  }
  std::printf(
      "vertex-face roots: %d checked, worst relative error time %.2e, normal+weights %.2e\n",
      outcome.checked, outcome.worstTime, outcome.worstJacobian);
  EXPECT_GE(outcome.checked, 40);
}

TEST(CollisionCcdDerivatives, VertexFaceOnAnEdgeOfTheFace) {
  // The vertex crosses the plane 0.5 thickness outside edge 0-1: the closest point is on the
  // edge and the normal is the (in-plane) separation direction.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Outcome outcome;
  const double thickness = 0.1;
  for (int trial = 0; trial < 60; ++trial) {
    PairPositions start, end;
    const Coords base = randomVertexFaceCrossing(rng, 0.5, Vec3(0.5, 0.5, 0.0), Vec3::Zero());
    unpack(base, start, end);
    // Move the vertex's path sideways in the face's plane at t = 0.5, away from corner 2.
    PairPositions mid;
    for (int k = 0; k < 4; ++k) mid[k] = 0.5 * (start[k] + end[k]);
    const Vec3 e = (mid[2] - mid[1]).normalized(), n = e.cross(mid[3] - mid[1]).normalized();
    const Vec3 out = n.cross(e);  // in the plane, perpendicular to edge 0-1, away from corner 2
    const Vec3 shift = 0.5 * thickness * out * ((mid[3] - mid[1]).dot(out) > 0 ? -1.0 : 1.0);
    start[0] += shift, end[0] += shift;
    const auto impact = vertexFaceCcd(start, end, thickness);
    ASSERT_TRUE(impact);
    EXPECT_EQ(impact->weights[3], 0.0);  // closest point on edge 0-1 (face corners 0, 1)
    check(ImpactKind::VertexFace, pack(start, end), thickness, ImpactTimeSource::CoplanarityRoot,
          outcome, 1e-7);
  }
  std::printf(
      "vertex-face on an edge: %d checked, worst relative error time %.2e, normal+weights "
      "%.2e\n",
      outcome.checked, outcome.worstTime, outcome.worstJacobian);
  EXPECT_GE(outcome.checked, 30);
}

TEST(CollisionCcdDerivatives, EdgeEdgeAtACoplanarityRoot) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Outcome outcome;
  for (int trial = 0; trial < 60; ++trial) {
    PairPositions start, end;
    for (int k = 0; k < 3; ++k) {
      start[k] = randomVec(rng, 1.0);
      end[k] = start[k] + randomVec(rng, 0.3);
    }
    // b1 is placed so that b passes through a's point s at tMeet, at u on b.
    const double tMeet = 0.2 + 0.6 * u(rng), s = 0.2 + 0.6 * u(rng), v = 0.2 + 0.6 * u(rng);
    auto at = [&](int k) { return start[k] + tMeet * (end[k] - start[k]); };
    const Vec3 meet = (1 - s) * at(0) + s * at(1);
    const Vec3 b1 = at(2) + (meet - at(2)) / v;  // meet = (1 - v) b0 + v b1
    const Vec3 d = randomVec(rng, 0.3);
    start[3] = b1 - tMeet * d, end[3] = b1 + (1 - tMeet) * d;
    check(ImpactKind::EdgeEdge, pack(start, end), 1e-3, ImpactTimeSource::CoplanarityRoot, outcome);
  }
  std::printf("edge-edge roots: %d checked, worst relative error time %.2e, normal+weights %.2e\n",
              outcome.checked, outcome.worstTime, outcome.worstJacobian);
  EXPECT_GE(outcome.checked, 40);
}

TEST(CollisionCcdDerivatives, EdgeEndpointBesideAnEdge) {
  // b's endpoint b0 passes 0.5 thickness beside a's interior when the pair is coplanar: the
  // closest point of b is clamped to its end (u = 0) and the normal is the separation direction.
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double thickness = 0.1;
  Outcome outcome;
  for (int trial = 0; trial < 60; ++trial) {
    PairPositions start, end;
    for (int k = 0; k < 2; ++k) {
      start[k] = randomVec(rng, 1.0);
      end[k] = start[k] + randomVec(rng, 0.3);
    }
    const double tMeet = 0.5, s = 0.3 + 0.4 * u(rng);
    PairPositions at;
    for (int k = 0; k < 2; ++k) at[k] = start[k] + tMeet * (end[k] - start[k]);
    const Vec3 da = (at[1] - at[0]).normalized();
    const Vec3 side = da.cross(randomVec(rng, 1.0)).normalized();
    // b lies in the plane of a and side, pointing away from a: b0 = a(s) + 0.5 thickness side.
    const Vec3 b0 = at[0] + s * (at[1] - at[0]) + 0.5 * thickness * side;
    const Vec3 b1 = b0 + (0.5 + u(rng)) * (side + 0.3 * da).normalized();
    const Vec3 v0 = randomVec(rng, 0.5), v1 = randomVec(rng, 0.5);
    start[2] = b0 - tMeet * v0, end[2] = b0 + (1 - tMeet) * v0;
    start[3] = b1 - tMeet * v1, end[3] = b1 + (1 - tMeet) * v1;
    const auto impact = edgeEdgeCcd(start, end, thickness);
    if (!impact || impact->weights[3] != 0.0) continue;  // another root came first
    check(ImpactKind::EdgeEdge, pack(start, end), thickness, ImpactTimeSource::CoplanarityRoot,
          outcome, 1e-7);
  }
  std::printf(
      "edge endpoint beside an edge: %d checked, worst relative error time %.2e, "
      "normal+weights %.2e\n",
      outcome.checked, outcome.worstTime, outcome.worstJacobian);
  EXPECT_GE(outcome.checked, 20);
}

TEST(CollisionCcdDerivatives, ProximityAtTheEndOfTheStep) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double thickness = 0.05;
  Outcome vf, ee;
  for (int trial = 0; trial < 40; ++trial) {
    // Vertex-face: the vertex ends 0.5 thickness above an interior point, from 1 above.
    PairPositions start, end;
    for (int k = 1; k < 4; ++k) {
      start[k] = randomVec(rng, 1.0);
      end[k] = start[k] + randomVec(rng, 0.3);
    }
    const double b1 = 0.2 + 0.3 * u(rng), b2 = 0.2 + 0.3 * u(rng);
    const Vec3 n = (end[2] - end[1]).cross(end[3] - end[1]).normalized();
    end[0] = (1 - b1 - b2) * end[1] + b1 * end[2] + b2 * end[3] + 0.5 * thickness * n;
    const Vec3 startFace = (1 - b1 - b2) * start[1] + b1 * start[2] + b2 * start[3];
    start[0] = startFace + (start[2] - start[1]).cross(start[3] - start[1]).normalized();
    check(ImpactKind::VertexFace, pack(start, end), thickness, ImpactTimeSource::EndProximity, vf);
    // Edge-edge: b ends 0.5 thickness from a's interior along their common perpendicular.
    PairPositions es, ee2;
    for (int k = 0; k < 4; ++k) {
      es[k] = randomVec(rng, 1.0);
      ee2[k] = es[k] + randomVec(rng, 0.3);
    }
    const double s = 0.3 + 0.4 * u(rng), v = 0.3 + 0.4 * u(rng);
    const Vec3 da = ee2[1] - ee2[0];
    const Vec3 db = (ee2[3] - ee2[2]).normalized();
    const Vec3 perp = da.cross(db).normalized();
    const Vec3 target = (1 - s) * ee2[0] + s * ee2[1] + 0.5 * thickness * perp;
    const Vec3 shiftEnd = target - ((1 - v) * ee2[2] + v * ee2[3]);
    ee2[2] += shiftEnd, ee2[3] += shiftEnd;
    check(ImpactKind::EdgeEdge, pack(es, ee2), thickness, ImpactTimeSource::EndProximity, ee);
  }
  std::printf(
      "end proximity: vertex-face %d, edge-edge %d checked, worst relative errors %.2e, "
      "%.2e\n",
      vf.checked, ee.checked, vf.worstJacobian, ee.worstJacobian);
  EXPECT_GE(vf.checked, 15);
  EXPECT_GE(ee.checked, 15);
}

TEST(CollisionCcdDerivatives, TimeOfImpactGradientHasLiangsFixedSign) {
  // The vertex falls from z = 1 to z = -1 through the fixed face z = 0: t = 0.5. Raising the
  // face's start height by dh (end unchanged), the height of the vertex over the face at t is
  // 1 - 2t - dh (1 - t) = 0, so dt/dh = -(1 - t) / 2 = -0.25; raising the vertex's start by dz,
  // 1 + dz (1 - t) - 2t = 0, so dt/dz = +0.25. Liang's Eq. 7 as printed gives the opposite signs.
  const PairPositions start = {Vec3(0.2, 0.3, 1.0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const PairPositions end = {Vec3(0.2, 0.3, -1.0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const PairGradient g = timeOfImpactGradient(start, end, 0.5);
  const double dtdh = g[5] + g[8] + g[11];  // start z of corners 1..3
  EXPECT_NEAR(dtdh, -0.25, 1e-14);
  // And the vertex's start z: 1 + dz(1 - t) - 2t = 0 -> dt/dz = (1 - t) / 2 = 0.25.
  EXPECT_NEAR(g[2], 0.25, 1e-14);
}

}  // namespace
}  // namespace weft::collision
