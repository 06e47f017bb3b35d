// Stretch (membrane) energy of one triangle: W = k A |F - R|^2 / 2 with R the closest matrix
// with orthonormal columns to the deformation gradient F (Bouaziz et al. 2014, DiffCloth).

#include <weft/mesh/GridMesh.h>
#include <weft/physics/StretchConstraint.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <random>

namespace weft {
namespace {

using Mat32 = Eigen::Matrix<double, 3, 2>;

// A scalene rest triangle, tilted out of every coordinate plane.
NodeMatrix restTriangle() {
  NodeMatrix x(3, 3);
  x << 0.1, 0.2, -0.3,  //
      1.3, 0.4, 0.1,    //
      0.4, 1.1, 0.6;
  return x;
}

TriangleIndices oneTriangle() {
  TriangleIndices t(1, 3);
  t << 0, 1, 2;
  return t;
}

constexpr double kStiffness = 250.0;

struct Evaluation {
  Mat32 f;        // deformation gradient, from the constraint's own selection rows (A x)
  Mat32 q;        // the projection p(x)
  double energy;  // as reported by the constraint
  double weight;
};

Evaluation evaluate(const StretchConstraint& c, const NodeMatrix& x) {
  NodeMatrix wp = NodeMatrix::Zero(2, 3);
  Evaluation e;
  e.energy = c.project(x, wp);
  e.weight = c.weights()[0];
  const NodeMatrix ax = c.selectionTransposed().transpose() * x;
  e.f.col(0) = ax.row(0).transpose();
  e.f.col(1) = ax.row(1).transpose();
  e.q.col(0) = wp.row(0).transpose() / e.weight;
  e.q.col(1) = wp.row(1).transpose() / e.weight;
  return e;
}

Mat3 randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

// The polar factor of F by SVD: the closest matrix with orthonormal columns, U V^T.
Mat32 polarBySvd(const Mat32& f) {
  // Thin factors need a dynamic-size matrix in Eigen.
  const Eigen::MatrixXd dynamic = f;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(dynamic, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return svd.matrixU() * svd.matrixV().transpose();
}

TEST(StretchConstraint, WeightIsStiffnessTimesRestArea) {
  const NodeMatrix x = restTriangle();
  const StretchConstraint c(x, oneTriangle(), {kStiffness});
  const double area = 0.5 * (Vec3(x.row(1) - x.row(0)).cross(Vec3(x.row(2) - x.row(0)))).norm();
  ASSERT_EQ(c.rowCount(), 2);
  EXPECT_NEAR(c.weights()[0], kStiffness * area, 1e-12);
  EXPECT_NEAR(c.weights()[1], kStiffness * area, 1e-12);
}

TEST(StretchConstraint, DeformationGradientMapsRestEdgesToCurrentEdges) {
  // F = [x1-x0, x2-x0] D^{-1} with D the rest edges in the rest frame T (at rest, F = T). So
  // F (T^T (X_b - X_a)) = x_b - x_a for every edge of the triangle.
  const NodeMatrix rest = restTriangle();
  const StretchConstraint c(rest, oneTriangle(), {kStiffness});
  NodeMatrix x = rest;
  x.row(1) += Eigen::RowVector3d(-0.1, 0.2, 0.05);
  x.row(2) += Eigen::RowVector3d(0.3, -0.2, 0.5);
  const Evaluation e = evaluate(c, x);
  const Mat32 frame = evaluate(c, rest).f;
  EXPECT_NEAR((frame.transpose() * frame - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-14);
  for (auto [a, b] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    const Eigen::Vector2d restEdge = frame.transpose() * (rest.row(b) - rest.row(a)).transpose();
    const Vec3 current = (x.row(b) - x.row(a)).transpose();
    EXPECT_NEAR((e.f * restEdge - current).norm(), 0.0, 1e-13) << a << "-" << b;
  }
}

TEST(StretchConstraint, RestStateHasZeroEnergyAndProjectsOntoF) {
  const NodeMatrix x = restTriangle();
  const StretchConstraint c(x, oneTriangle(), {kStiffness});
  const Evaluation e = evaluate(c, x);
  EXPECT_NEAR(e.energy, 0.0, 1e-13 * e.weight);
  EXPECT_NEAR((e.q - e.f).norm(), 0.0, 1e-14);
  EXPECT_NEAR((e.f.transpose() * e.f - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-14);
}

TEST(StretchConstraint, RigidMotionKeepsZeroEnergyAndProjectionEqualsF) {
  const NodeMatrix rest = restTriangle();
  const StretchConstraint c(rest, oneTriangle(), {kStiffness});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 r = randomRotation(rng);
    const Eigen::RowVector3d t(u(rng), u(rng), u(rng));
    NodeMatrix x = rest * r.transpose();
    x.rowwise() += t;
    const Evaluation e = evaluate(c, x);
    EXPECT_NEAR(e.energy, 0.0, 1e-12 * e.weight) << "trial " << trial;
    EXPECT_NEAR((e.q - e.f).norm(), 0.0, 1e-12) << "trial " << trial;
  }
}

TEST(StretchConstraint, DeformedProjectionIsThePolarFactor) {
  const NodeMatrix rest = restTriangle();
  const StretchConstraint c(rest, oneTriangle(), {kStiffness});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int trial = 0; trial < 50; ++trial) {
    // Random deformation (stretch, shear, compression) followed by a random rigid motion.
    NodeMatrix x = rest;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) x(i, k) += u(rng);
    x = x * randomRotation(rng).transpose();
    const Evaluation e = evaluate(c, x);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // Orthonormal columns.
    EXPECT_NEAR((e.q.transpose() * e.q - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-12);
    // The closest such matrix: the SVD polar factor.
    EXPECT_NEAR((e.q - polarBySvd(e.f)).norm(), 0.0, 1e-9);
    // The reported energy is w/2 |F - p|^2 for this projection.
    EXPECT_NEAR(e.energy, 0.5 * e.weight * (e.f - e.q).squaredNorm(), 1e-10 * (1 + e.energy));
    // And the static routine agrees with what the constraint projects.
    const Mat32 q2 = StretchConstraint::project(e.f, x.row(0).transpose(), x.row(1).transpose(),
                                                x.row(2).transpose());
    EXPECT_NEAR((q2 - e.q).norm(), 0.0, 1e-12);
  }
}

TEST(StretchConstraint, ProjectionBeatsEveryOtherOrthonormalFrame) {
  const NodeMatrix rest = restTriangle();
  const StretchConstraint c(rest, oneTriangle(), {kStiffness});
  NodeMatrix x = rest;
  x.row(1) += Eigen::RowVector3d(0.5, 0.1, -0.2);  // stretch one edge by about half
  x.row(2) += Eigen::RowVector3d(-0.1, 0.3, 0.0);
  const Evaluation e = evaluate(c, x);
  EXPECT_GT(e.energy, 0.0);
  std::mt19937 rng(3);
  const double best = (e.f - e.q).norm();
  for (int trial = 0; trial < 200; ++trial) {
    const Mat32 other = randomRotation(rng).leftCols<2>();
    EXPECT_GE((e.f - other).norm(), best - 1e-12);
  }
}

TEST(StretchConstraint, UniformScalingEnergyMatchesClosedForm) {
  // Scaling a whole mesh by s gives F = s R, projection R and W = k A (s - 1)^2 summed.
  const TriangleMesh grid = makeGrid(1.2, 0.8, 4, 3);
  const std::vector<double> stiffness(grid.triangleCount(), kStiffness);
  const StretchConstraint c(grid.vertices, grid.triangles, stiffness);
  for (double s : {0.5, 0.9, 1.0, 1.1, 2.0}) {
    NodeMatrix wp = NodeMatrix::Zero(c.rowCount(), 3);
    const double energy = c.project(s * grid.vertices, wp);
    EXPECT_NEAR(energy, kStiffness * grid.totalArea() * (s - 1) * (s - 1), 1e-10) << "s = " << s;
  }
}

TEST(StretchConstraint, CollapsedTriangleStaysFinite) {
  // A triangle squashed onto a line or a point (as in a crumpled cloth) must give a finite
  // projection with orthonormal columns, never NaN.
  const NodeMatrix rest = restTriangle();
  const StretchConstraint c(rest, oneTriangle(), {kStiffness});
  NodeMatrix line = rest;
  line.row(2) = 0.5 * (rest.row(0) + rest.row(1));
  NodeMatrix point = NodeMatrix::Zero(3, 3);
  NodeMatrix edge = rest;
  edge.row(1) = rest.row(0);
  for (const NodeMatrix* x : {&line, &point, &edge}) {
    const Evaluation e = evaluate(c, *x);
    EXPECT_TRUE(e.q.allFinite());
    EXPECT_TRUE(std::isfinite(e.energy));
    EXPECT_NEAR((e.q.transpose() * e.q - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-12);
  }
}

// The projection's derivative (applyDerivative, prepared at x) against central differences of
// project, for stretched, compressed, sheared and bent-out-of-plane triangles. The `definite`
// variant clamps dQ (the Newton contact solve's and the adjoint's K+): where every singular value
// of F is at least 1 it is the same derivative, where one is below 1 it must differ.
TEST(StretchConstraint, ProjectionDerivativeMatchesFiniteDifferences) {
  const NodeMatrix rest = restTriangle();
  StretchConstraint c(rest, oneTriangle(), {kStiffness});
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const Mat3 stretch = Eigen::Vector3d(1.3, 1.1, 1.2).asDiagonal();
  const Mat3 compress = Eigen::Vector3d(0.6, 0.8, 0.7).asDiagonal();
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.4;
  for (const Mat3& deform : {stretch, compress, shear}) {
    NodeMatrix x = rest * (randomRotation(rng) * deform).transpose();
    x.row(2) += 0.05 * Vec3(normal(rng), normal(rng), normal(rng)).transpose();
    NodeMatrix dx(3, 3);
    for (int i = 0; i < 9; ++i) dx(i / 3, i % 3) = normal(rng);
    const double h = 1e-6;
    NodeMatrix plus = NodeMatrix::Zero(2, 3), minus = NodeMatrix::Zero(2, 3);
    c.project(x + h * dx, plus);
    c.project(x - h * dx, minus);
    const NodeMatrix difference = (plus - minus) / (2.0 * h);
    NodeMatrix exact = NodeMatrix::Zero(2, 3), clamped = NodeMatrix::Zero(2, 3);
    c.prepareDerivative(x, false);
    c.applyDerivative(dx, exact);
    EXPECT_LT((exact - difference).norm(), 1e-7 * difference.norm());
    c.prepareDerivative(x, true);
    c.applyDerivative(dx, clamped);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(evaluate(c, x).f));
    if (svd.singularValues().minCoeff() >= 1.0)
      EXPECT_LT((clamped - exact).norm(), 1e-12 * exact.norm());
    else
      EXPECT_GT((clamped - exact).norm(), 1e-3 * exact.norm());
  }
}

}  // namespace
}  // namespace weft
