// K = P (x) I_3 - h^2 Delta P assembled from the constraints' element blocks (HessianAssembly)
// against the matrix-free product the Newton and adjoint solves use (P x - h^2 sum A^T w D A x),
// on a curved cloth whose bending projections are not zero, with the exact and the clamped
// (`definite`) derivatives.

#include <weft/mesh/GridMesh.h>
#include <weft/physics/BendingConstraint.h>
#include <weft/physics/HessianAssembly.h>
#include <weft/physics/StretchConstraint.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace weft {
namespace {

constexpr double kStep = 0.01;  // h (s)

struct CurvedCloth {
  NodeMatrix rest;
  TriangleIndices triangles;
  std::vector<std::unique_ptr<ProjectiveConstraint>> constraints;
  Eigen::SparseMatrix<double> system;  // P
};

// A 7 x 5 quad grid rolled a quarter turn onto a cylinder (bent hinges at rest) with stretch
// and bending; P = M + h^2 sum A^T W A over stretch, and over bending too when `bendingInP`.
CurvedCloth curvedCloth(bool bendingInP) {
  CurvedCloth c;
  const TriangleMesh grid = makeGrid(0.7, 0.5, 7, 5);
  c.rest = grid.vertices;
  const double radius = 0.45;
  for (Eigen::Index i = 0; i < c.rest.rows(); ++i) {
    const double angle = c.rest(i, 0) / radius;
    c.rest(i, 0) = radius * std::sin(angle);
    c.rest(i, 1) = radius * (1.0 - std::cos(angle));
  }
  c.triangles = grid.triangles;
  auto stretch = [&] {
    return std::make_unique<StretchConstraint>(
        c.rest, c.triangles,
        std::vector<double>(static_cast<std::size_t>(c.triangles.rows()), 300.0));
  };
  auto bending = [&] {
    return std::make_unique<BendingConstraint>(buildHinges(c.rest, c.triangles, 0.02),
                                               static_cast<int>(c.rest.rows()));
  };
  c.constraints.push_back(stretch());
  c.constraints.push_back(bending());
  std::vector<std::unique_ptr<ProjectiveConstraint>> inP;
  inP.push_back(stretch());
  if (bendingInP) inP.push_back(bending());
  c.system = assembleSystemMatrix(Eigen::VectorXd::Constant(c.rest.rows(), 0.002), inP, kStep);
  return c;
}

// The rest shape squeezed along X (compressed triangles: the clamping has work to do), twisted
// and perturbed.
NodeMatrix deformed(const NodeMatrix& rest) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  NodeMatrix x = rest;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    x(i, 0) *= 0.8;
    x(i, 1) += 0.2 * x(i, 0) * x(i, 2);
    for (int d = 0; d < 3; ++d) x(i, d) += noise(random);
  }
  return x;
}

// P x - h^2 sum_c A_c^T w_c D_c A_c x, as Simulator::multiplyNewtonMatrix computes it.
NodeMatrix product(const CurvedCloth& c, const NodeMatrix& x) {
  NodeMatrix out = c.system * x;
  for (const auto& family : c.constraints) {
    NodeMatrix rows(family->rowCount(), 3);
    family->applyDerivative(x, rows);
    family->gather(rows, -kStep * kStep, out);
  }
  return out;
}

TEST(HessianAssembly, MatchesTheMatrixFreeProductWithExactAndClampedDerivatives) {
  CurvedCloth c = curvedCloth(true);
  const NodeMatrix x = deformed(c.rest);
  ASSERT_TRUE(c.constraints[1]->hasDerivative()) << "the rolled cloth's hinges are bent at rest";
  HessianAssembly assembly(c.system);
  const int m = static_cast<int>(c.rest.rows());
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  for (bool definite : {false, true}) {
    for (auto& family : c.constraints) family->prepareDerivative(x, definite);
    Eigen::SparseMatrix<double> k;
    assembly.assemble(c.constraints, -kStep * kStep, k);
    ASSERT_EQ(k.rows(), 3 * m);
    // The derivative is not negligible next to P: the test would see a dropped block.
    NodeMatrix probe(m, 3);
    for (Eigen::Index i = 0; i < probe.size(); ++i) probe.data()[i] = normal(random);
    const NodeMatrix expected = product(c, probe);
    const NodeMatrix plain = c.system * probe;
    EXPECT_GT((expected - plain).norm(), 1e-3 * plain.norm());
    const Eigen::Map<const Eigen::VectorXd> flat(probe.data(), 3 * m);
    const Eigen::VectorXd assembled = k * flat;
    const Eigen::Map<const Eigen::VectorXd> reference(expected.data(), 3 * m);
    EXPECT_LT((assembled - reference).norm(), 1e-12 * reference.norm()) << "definite " << definite;
    const Eigen::SparseMatrix<double> kt = k.transpose();
    EXPECT_LT((k - kt).norm(), 1e-12 * k.norm()) << "definite " << definite;
    // Assembling again into the same matrix (values overwritten in place) gives the same K.
    const Eigen::SparseMatrix<double> first = k;
    assembly.assemble(c.constraints, -kStep * kStep, k);
    EXPECT_EQ((k - first).norm(), 0.0);
  }
}

TEST(HessianAssembly, RefusesAnElementThatCouplesNodesOutsidePsPattern) {
  // Without bending in P, a hinge's two wing nodes share no entry of P.
  CurvedCloth c = curvedCloth(false);
  for (auto& family : c.constraints) family->prepareDerivative(c.rest, false);
  HessianAssembly assembly(c.system);
  Eigen::SparseMatrix<double> k;
  EXPECT_THROW(assembly.assemble(c.constraints, -kStep * kStep, k), std::logic_error);
}

}  // namespace
}  // namespace weft
