// Bending of one hinge (two triangles sharing an edge): the cotangent-weighted curvature vector
// e = sum_k w_k x_k, projected to keep the rest curvature magnitude; W = w/2 |e - p|^2.

#include <weft/mesh/GridMesh.h>
#include <weft/physics/BendingConstraint.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace weft {
namespace {

constexpr double kBend = 0.01;  // N m

// Hinge along the X axis from node 0 to node 1, wing node 2 at +Z (triangle 0 = (0, 1, 2)),
// wing node 3 at -Z (triangle 1 = (1, 0, 3)), both in the XZ plane before folding. The wing
// of node 3 is folded up about the hinge by `foldDeg` (0 = flat).
NodeMatrix hinge(double foldDeg) {
  NodeMatrix x(4, 3);
  x << 0.0, 0.0, 0.0,  //
      1.0, 0.0, 0.0,   //
      0.45, 0.0, 0.8,  //
      0.6, 0.0, -0.7;
  const Eigen::AngleAxisd fold(foldDeg * M_PI / 180.0, Vec3::UnitX());
  x.row(3) = (fold * Vec3(x.row(3).transpose())).transpose();
  return x;
}

TriangleIndices hingeTriangles() {
  TriangleIndices t(2, 3);
  t << 0, 1, 2, 1, 0, 3;
  return t;
}

double energy(const BendingConstraint& c, const NodeMatrix& x) {
  NodeMatrix wp = NodeMatrix::Zero(c.rowCount(), 3);
  return c.project(x, wp);
}

BendingConstraint makeConstraint(const NodeMatrix& rest) {
  return BendingConstraint(buildHinges(rest, hingeTriangles(), kBend), 4);
}

// Cotangent of the angle at `apex` of the triangle (apex, p, q), via atan2: an independent
// route to the weights.
double cotAt(const Vec3& apex, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - apex, v = q - apex;
  return 1.0 / std::tan(std::atan2(u.cross(v).norm(), u.dot(v)));
}

NodeMatrix rigidlyMoved(const NodeMatrix& x, std::mt19937& rng) {
  std::normal_distribution<double> n;
  const Mat3 r = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  NodeMatrix y = x * r.transpose();
  y.rowwise() += Eigen::RowVector3d(n(rng), n(rng), n(rng));
  return y;
}

TEST(BendingConstraint, HingeWeightsAreTheCotangentFormula) {
  const NodeMatrix x = hinge(0.0);
  const auto hinges = buildHinges(x, hingeTriangles(), kBend);
  ASSERT_EQ(hinges.size(), 1u);
  const Hinge& h = hinges[0];
  ASSERT_EQ(h.nodes[0], 0);
  ASSERT_EQ(h.nodes[1], 1);
  ASSERT_EQ(h.nodes[2], 2);
  ASSERT_EQ(h.nodes[3], 3);
  const Vec3 x0 = x.row(0), x1 = x.row(1), x2 = x.row(2), x3 = x.row(3);
  const double c02 = cotAt(x0, x1, x2), c12 = cotAt(x1, x0, x2);  // triangle 0, at the edge ends
  const double c03 = cotAt(x0, x1, x3), c13 = cotAt(x1, x0, x3);  // triangle 1
  // Each edge end gets the cotangents of the angles at the other end; the wings the negated sums.
  EXPECT_NEAR(h.cot[0], c12 + c13, 1e-12);
  EXPECT_NEAR(h.cot[1], c02 + c03, 1e-12);
  EXPECT_NEAR(h.cot[2], -(c02 + c12), 1e-12);
  EXPECT_NEAR(h.cot[3], -(c03 + c13), 1e-12);
  const double areas = 0.5 * ((x1 - x0).cross(x2 - x0).norm() + (x1 - x0).cross(x3 - x0).norm());
  EXPECT_NEAR(h.weight, 3.0 * kBend / areas, 1e-12);
  EXPECT_EQ(h.restNorm, 0.0);
}

TEST(BendingConstraint, FlatHingeHasZeroEnergyUnderAnyAffineMap) {
  // The curvature vector of a flat rest hinge vanishes for every planar placement of it: rigid
  // motions, but also in-plane stretch and shear must not be seen as bending.
  const NodeMatrix rest = hinge(0.0);
  const BendingConstraint c = makeConstraint(rest);
  EXPECT_NEAR(energy(c, rest), 0.0, 1e-20);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    EXPECT_NEAR(energy(c, rigidlyMoved(rest, rng)), 0.0, 1e-20) << "rigid " << trial;
    Mat3 a = Mat3::Identity();
    a(0, 0) = 1.0 + 0.1 * trial;
    a(0, 2) = 0.05 * trial;  // shear in the XZ plane
    a(2, 2) = 1.0 - 0.03 * trial;
    EXPECT_NEAR(energy(c, rigidlyMoved(rest * a.transpose(), rng)), 0.0, 1e-20)
        << "affine " << trial;
  }
}

TEST(BendingConstraint, FoldedFlatHingeEnergyIsPositiveAndGrowsWithAngle) {
  const BendingConstraint c = makeConstraint(hinge(0.0));
  const Hinge& h = c.hinges()[0];
  double previous = 0.0;
  for (double angle : {5.0, 15.0, 30.0, 60.0, 90.0, 120.0, 150.0}) {
    const NodeMatrix x = hinge(angle);
    const double e = energy(c, x);
    EXPECT_GT(e, previous) << angle << " degrees";
    // Flat rest: projection 0, so W = w/2 |sum_k w_k x_k|^2 exactly.
    Vec3 curvature = Vec3::Zero();
    for (int k = 0; k < 4; ++k) curvature += h.cot[k] * x.row(k).transpose();
    EXPECT_NEAR(e, 0.5 * h.weight * curvature.squaredNorm(), 1e-14 * (1 + e));
    previous = e;
  }
  // Small folds: quadratic in the angle.
  EXPECT_NEAR(energy(c, hinge(2.0)) / energy(c, hinge(1.0)), 4.0, 1e-3);
}

TEST(BendingConstraint, CurvedRestHingeIsZeroAtRestAndUnderRigidMotion) {
  const NodeMatrix rest = hinge(40.0);
  const BendingConstraint c = makeConstraint(rest);
  ASSERT_GT(c.hinges()[0].restNorm, 0.0);
  const double scale = c.hinges()[0].weight * c.hinges()[0].restNorm * c.hinges()[0].restNorm;
  EXPECT_NEAR(energy(c, rest), 0.0, 1e-13 * scale);
  std::mt19937 rng(9);
  for (int trial = 0; trial < 20; ++trial)
    EXPECT_NEAR(energy(c, rigidlyMoved(rest, rng)), 0.0, 1e-12 * scale) << "trial " << trial;
  // Flattening or folding further both bend it away from its rest shape.
  EXPECT_GT(energy(c, hinge(0.0)), 1e-6 * scale);
  EXPECT_GT(energy(c, hinge(80.0)), 1e-6 * scale);
  EXPECT_GT(energy(c, hinge(80.0)), energy(c, hinge(60.0)));
}

BendingConstraint makeOriented(const NodeMatrix& rest) {
  return BendingConstraint(buildHinges(rest, hingeTriangles(), kBend, /*oriented=*/true), 4);
}

TEST(BendingConstraint, OrientedHingeIsZeroAtRestAndUnderRigidMotion) {
  const NodeMatrix rest = hinge(40.0);
  BendingConstraint c = makeOriented(rest);
  ASSERT_TRUE(c.hinges()[0].oriented);
  ASSERT_TRUE(c.dependsOnStart());
  const double scale = c.hinges()[0].weight * c.hinges()[0].restNorm * c.hinges()[0].restNorm;
  c.beginStep(0.0, rest);
  EXPECT_NEAR(energy(c, rest), 0.0, 1e-13 * scale);
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const NodeMatrix moved = rigidlyMoved(rest, rng);
    c.beginStep(0.0, moved);  // the frame follows the step's start
    EXPECT_NEAR(energy(c, moved), 0.0, 1e-12 * scale) << "trial " << trial;
  }
}

TEST(BendingConstraint, OrientedHingeTellsWhichSideItCurvesTo) {
  // Folded the other way by as much (-40 degrees against the rest's 40): the magnitude model
  // sees the rest curvature's magnitude and no energy; the oriented one the full reversal.
  const NodeMatrix rest = hinge(40.0), reversed = hinge(-40.0);
  const BendingConstraint magnitude = makeConstraint(rest);
  BendingConstraint oriented = makeOriented(rest);
  const Hinge& h = oriented.hinges()[0];
  const double scale = h.weight * h.restNorm * h.restNorm;
  EXPECT_NEAR(energy(magnitude, reversed), 0.0, 1e-12 * scale);
  oriented.beginStep(0.0, reversed);
  EXPECT_GT(energy(oriented, reversed), 0.5 * scale);  // |e - p| near 2 |e_rest|: ~2 scale
  // Flattened: the magnitude model's energy peaks there, with its force turning round; the
  // oriented one pushes back towards the rest side, and its energy is below the reversed one's.
  oriented.beginStep(0.0, hinge(0.0));
  EXPECT_LT(energy(oriented, hinge(0.0)), energy(oriented, reversed));
}

TEST(BendingConstraint, OrientedHingeHasNoDerivativeWithinAStep) {
  const NodeMatrix rest = hinge(40.0);
  BendingConstraint c = makeOriented(rest);
  const NodeMatrix start = hinge(25.0), x = hinge(10.0);
  c.beginStep(0.0, start);
  NodeMatrix wp0 = NodeMatrix::Zero(1, 3), wp1 = NodeMatrix::Zero(1, 3);
  c.project(x, wp0);
  c.project(hinge(70.0), wp1);
  EXPECT_LT((wp0 - wp1).norm(), 1e-15 * wp0.norm()) << "p is set by the step's start alone";
  c.prepareDerivative(x, false);
  NodeMatrix dx = NodeMatrix::Random(4, 3), rows = NodeMatrix::Ones(1, 3);
  c.applyDerivative(dx, rows);
  EXPECT_EQ(rows.norm(), 0.0);
}

TEST(BendingConstraint, OrientedStartGradientMatchesFiniteDifferences) {
  // addStartGradient: out += scale (dp/dx_n)^T w (A q). Against central differences of
  // f(x_n) = sum (w p(x_n)) . (A q) along random directions, from asymmetric starts.
  const NodeMatrix rest = hinge(40.0);
  BendingConstraint c = makeOriented(rest);
  const Hinge& h = c.hinges()[0];
  std::mt19937 rng(11);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 10; ++trial) {
    NodeMatrix start = rigidlyMoved(hinge(15.0 + 7.0 * trial), rng);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) start(i, k) += 0.05 * n(rng);
    NodeMatrix q(4, 3), direction(4, 3);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) q(i, k) = n(rng), direction(i, k) = n(rng);
    Vec3 aq = Vec3::Zero();
    for (int k = 0; k < 4; ++k) aq += h.cot[k] * q.row(h.nodes[k]).transpose();
    auto f = [&](const NodeMatrix& s) {
      c.beginStep(0.0, s);
      NodeMatrix wp = NodeMatrix::Zero(1, 3);
      c.project(s, wp);
      return wp.row(0).dot(aq.transpose());
    };
    const double eps = 1e-6;
    const double fd = (f(start + eps * direction) - f(start - eps * direction)) / (2.0 * eps);
    NodeMatrix out = NodeMatrix::Zero(4, 3);
    c.addStartGradient(start, q, 1.0, out);
    const double analytic = (out.array() * direction.array()).sum();
    EXPECT_NEAR(analytic, fd, 1e-6 * std::max(1.0, std::abs(fd))) << "trial " << trial;
  }
}

TEST(BendingConstraint, GridHasOneHingePerInteriorEdge) {
  const TriangleMesh grid = makeGrid(1.0, 1.0, 3, 4);
  const auto hinges = buildHinges(grid.vertices, grid.triangles, kBend);
  int interior = 0;
  for (const MeshEdge& e : buildEdges(grid)) interior += e.faces.size() == 2;
  EXPECT_EQ(static_cast<int>(hinges.size()), interior);
  const BendingConstraint c(hinges, grid.vertexCount());
  EXPECT_NEAR(energy(c, grid.vertices), 0.0, 1e-20);
}

}  // namespace
}  // namespace weft
