// The two uses of SparseCholesky: exact solves with P (simplicial, double) and the single-
// precision supernodal factor that preconditions GMRES with K+ (SparseCholesky.h).

#include <weft/physics/SparseCholesky.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace weft {
namespace {

// A symmetric positive definite matrix with a cloth's structure: an n x n grid of nodes, each
// coupled to its 8 neighbours, as 3 x 3 blocks when `block` (the shape of K+ = P (x) I - Delta P).
Eigen::SparseMatrix<double> gridMatrix(int n, bool block, double shift = 0.0, unsigned seed = 1) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coupling(0.1, 1.0);
  const int d = block ? 3 : 1;
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> diagonal(static_cast<std::size_t>(n * n * d), 1.0 + shift);
  auto couple = [&](int a, int b) {
    for (int k = 0; k < d; ++k)
      for (int l = 0; l < d; ++l) {
        const double w = (k == l ? 1.0 : 0.2) * coupling(random);
        entries.emplace_back(d * a + k, d * b + l, -w);
        entries.emplace_back(d * b + l, d * a + k, -w);
        diagonal[d * a + k] += std::abs(w);  // diagonally dominant: positive definite
        diagonal[d * b + l] += std::abs(w);
      }
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j;
      if (j + 1 < n) couple(a, a + 1);
      if (i + 1 < n) couple(a, a + n);
      if (i + 1 < n && j + 1 < n) couple(a, a + n + 1);
      if (i + 1 < n && j > 0) couple(a, a + n - 1);
    }
  for (std::size_t k = 0; k < diagonal.size(); ++k) entries.emplace_back(k, k, diagonal[k]);
  Eigen::SparseMatrix<double> a(n * n * d, n * n * d);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

double relativeResidual(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& x,
                        const Eigen::MatrixXd& b) {
  return (a * x - b).norm() / b.norm();
}

TEST(SparseCholesky, SolvesExactlyForOneTwoAndThreeRightHandSides) {
  const Eigen::SparseMatrix<double> a = gridMatrix(20, false);
  SparseCholesky cholesky;
  ASSERT_TRUE(cholesky.factorize(a));
  EXPECT_GT(cholesky.factorEntries(), static_cast<double>(a.rows()));
  for (int columns : {1, 2, 3}) {
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows(), columns);
    Eigen::MatrixXd x = b;
    cholesky.solveInPlace(x.data(), columns);
    EXPECT_LT(relativeResidual(a, x, b), 1e-13) << columns << " columns";
  }
}

// The preconditioner's factor: simplicial where CHOLMOD finds too few flops per entry for
// supernodes, double-precision panels while L fits in 16 MB, single-precision panels beyond
// (close to the exact solve, about 1e-7 relative).
void expectPreconditionerSolves(int n, SparseCholesky::Layout layout, double below, double above) {
  const Eigen::SparseMatrix<double> a = gridMatrix(n, true);
  SparseCholesky exact, preconditioner(SparseCholesky::Use::Preconditioner);
  ASSERT_TRUE(exact.factorize(a));
  ASSERT_TRUE(preconditioner.factorize(a));
  EXPECT_EQ(exact.layout(), SparseCholesky::Layout::Simplicial);
  EXPECT_EQ(preconditioner.layout(), layout);
  for (int columns : {1, 3}) {
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows(), columns);
    Eigen::MatrixXd x = b, y = b;
    exact.solveInPlace(x.data(), columns);
    preconditioner.solveInPlace(y.data(), columns);
    EXPECT_LT(relativeResidual(a, y, b), below) << columns << " columns";
    EXPECT_GT(relativeResidual(a, y, b), above) << columns << " columns";
    EXPECT_LT((x - y).norm() / x.norm(), std::max(below, 1e-12));
  }
  // Nested dissection was among the orderings tried: on a larger grid it fills L less than AMD.
  EXPECT_LE(preconditioner.factorEntries(), exact.factorEntries());
  if (n >= 32) {
    EXPECT_LT(preconditioner.factorEntries(), exact.factorEntries());
  }
}

TEST(SparseCholesky, PreconditionerFactorOfASmallMatrixIsSimplicial) {
  expectPreconditionerSolves(8, SparseCholesky::Layout::Simplicial, 1e-12, 0.0);
}

TEST(SparseCholesky, PreconditionerFactorOfAMediumMatrixIsInDoublePanels) {
  expectPreconditionerSolves(32, SparseCholesky::Layout::PanelsDouble, 1e-12, 0.0);
}

TEST(SparseCholesky, PreconditionerFactorOfALargeMatrixIsInSinglePanels) {
  expectPreconditionerSolves(96, SparseCholesky::Layout::PanelsSingle, 1e-5, 1e-12);
}

// K+'s unknowns are coordinate-major (d m + node, a NodeMatrix's storage). Ordering the node
// graph and keeping each node's three unknowns together (orderByNodes) must find about as
// little fill as CHOLMOD ordering the whole matrix, and solve the same.
TEST(SparseCholesky, NodeGraphOrderingFindsAsLittleFillAsOrderingTheWholeMatrix) {
  const int n = 32, m = n * n;
  const Eigen::SparseMatrix<double> nodeMajor = gridMatrix(n, true);
  Eigen::VectorXi toCoordinateMajor(3 * m);
  for (int i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d) toCoordinateMajor[3 * i + d] = d * m + i;
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm(toCoordinateMajor);
  Eigen::SparseMatrix<double> a;
  a = nodeMajor.twistedBy(perm);
  SparseCholesky whole(SparseCholesky::Use::Preconditioner),
      byNodes(SparseCholesky::Use::Preconditioner);
  ASSERT_TRUE(whole.factorize(a));
  byNodes.orderByNodes(gridMatrix(n, false));
  ASSERT_TRUE(byNodes.factorize(a));
  EXPECT_LT(byNodes.factorEntries(), 1.1 * whole.factorEntries());
  EXPECT_LT(byNodes.factorFlops(), 1.2 * whole.factorFlops());
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows(), 3);
  Eigen::MatrixXd x = b;
  byNodes.solveInPlace(x.data(), 3);
  EXPECT_LT(relativeResidual(a, x, b), 1e-12);
}

TEST(SparseCholesky, RefactorisesNewValuesOnTheSamePattern) {
  for (SparseCholesky::Use use :
       {SparseCholesky::Use::Solve, SparseCholesky::Use::Preconditioner}) {
    SparseCholesky cholesky(use);
    ASSERT_TRUE(cholesky.factorize(gridMatrix(12, true, 0.0, 1)));
    const Eigen::SparseMatrix<double> second = gridMatrix(12, true, 5.0, 2);
    ASSERT_TRUE(cholesky.factorize(second));
    const Eigen::VectorXd b = Eigen::VectorXd::Random(second.rows());
    Eigen::VectorXd x = b;
    cholesky.solveInPlace(x);
    EXPECT_LT(relativeResidual(second, x, b), 1e-5);
  }
}

TEST(SparseCholesky, RefusesAnIndefiniteMatrix) {
  for (SparseCholesky::Use use :
       {SparseCholesky::Use::Solve, SparseCholesky::Use::Preconditioner}) {
    SparseCholesky cholesky(use);
    ASSERT_TRUE(cholesky.factorize(gridMatrix(8, true)));
    Eigen::SparseMatrix<double> indefinite = gridMatrix(8, true);
    indefinite.coeffRef(40, 40) = -1.0;
    EXPECT_FALSE(cholesky.factorize(indefinite));
    EXPECT_FALSE(cholesky.factorized());
  }
}

}  // namespace
}  // namespace weft
