// SolutionHistory: the starting point of a backward step's solve combines previous solutions
// so that their products match the new right-hand side (least squares). With a fixed matrix a
// right-hand side in the span of kept products gives back the exact solution; the history keeps
// only its newest pairs; degenerate pairs are refused; nearly parallel ones stay harmless.

#include <weft/diff/SolutionHistory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace weft {
namespace {

constexpr int kNodes = 20;

// A fixed symmetric positive definite operator on m x 3 blocks (as K is on one step).
struct Operator {
  Eigen::MatrixXd a;
  explicit Operator(unsigned seed) {
    std::mt19937 gen(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::MatrixXd b(3 * kNodes, 3 * kNodes);
    for (int i = 0; i < b.rows(); ++i)
      for (int j = 0; j < b.cols(); ++j) b(i, j) = n(gen);
    a = b * b.transpose() + 3.0 * kNodes * Eigen::MatrixXd::Identity(3 * kNodes, 3 * kNodes);
  }
  NodeMatrix operator()(const NodeMatrix& z) const {
    NodeMatrix out(kNodes, 3);
    Eigen::Map<Eigen::VectorXd>(out.data(), 3 * kNodes) =
        a * Eigen::Map<const Eigen::VectorXd>(z.data(), 3 * kNodes);
    return out;
  }
};

NodeMatrix randomBlock(unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  NodeMatrix b(kNodes, 3);
  for (int i = 0; i < kNodes; ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = n(gen);
  return b;
}

TEST(SolutionHistory, RecoversTheSolutionOfACombinationOfKeptRightHandSides) {
  const Operator k(1);
  SolutionHistory history(4);
  const NodeMatrix z1 = randomBlock(2), z2 = randomBlock(3), z3 = randomBlock(4);
  for (const NodeMatrix* z : {&z1, &z2, &z3}) history.add(*z, k(*z));
  EXPECT_EQ(history.size(), 3);
  const NodeMatrix expected = 2.0 * z1 - 0.5 * z3;
  NodeMatrix guess;
  ASSERT_TRUE(history.guess(k(expected), guess));
  EXPECT_LT((guess - expected).norm(), 1e-10 * expected.norm());
  // A right-hand side outside the span: the guess is the least-squares combination, so its
  // residual is orthogonal to every kept product and no larger than the right-hand side.
  const NodeMatrix g = randomBlock(5);
  ASSERT_TRUE(history.guess(g, guess));
  const NodeMatrix residual = g - k(guess);
  for (const NodeMatrix* z : {&z1, &z2, &z3})
    EXPECT_LT(std::abs((residual.array() * k(*z).array()).sum()),
              1e-10 * residual.norm() * k(*z).norm());
  EXPECT_LT(residual.norm(), g.norm());
}

TEST(SolutionHistory, KeepsOnlyTheNewestPairs) {
  const Operator k(6);
  SolutionHistory history(2);
  const NodeMatrix z1 = randomBlock(7), z2 = randomBlock(8), z3 = randomBlock(9);
  for (const NodeMatrix* z : {&z1, &z2, &z3}) history.add(*z, k(*z));
  EXPECT_EQ(history.size(), 2);
  NodeMatrix guess;
  ASSERT_TRUE(history.guess(k(z2 + z3), guess));
  EXPECT_LT((guess - (z2 + z3)).norm(), 1e-10 * (z2 + z3).norm());
  // z1 dropped out: its right-hand side is no longer matched.
  ASSERT_TRUE(history.guess(k(z1), guess));
  EXPECT_GT((guess - z1).norm(), 0.1 * z1.norm());
}

TEST(SolutionHistory, RefusesDegeneratePairs) {
  const Operator k(10);
  SolutionHistory history(3);
  NodeMatrix guess = NodeMatrix::Constant(kNodes, 3, 7.0);
  EXPECT_FALSE(history.guess(randomBlock(11), guess));
  EXPECT_EQ(guess(0, 0), 7.0);  // untouched
  history.add(NodeMatrix::Zero(kNodes, 3), NodeMatrix::Zero(kNodes, 3));
  NodeMatrix bad = randomBlock(12);
  bad(3, 1) = std::numeric_limits<double>::quiet_NaN();
  history.add(bad, k(randomBlock(12)));
  EXPECT_EQ(history.size(), 0);
  SolutionHistory none(0);
  none.add(randomBlock(13), k(randomBlock(13)));
  EXPECT_EQ(none.size(), 0);
}

// Consecutive adjoints are nearly parallel: the normal equations' cut-off must keep the guess
// finite and at least as good as the best single kept solution.
TEST(SolutionHistory, NearlyParallelSolutionsStayHarmless) {
  const Operator k(14);
  SolutionHistory history(4);
  const NodeMatrix z = randomBlock(15);
  for (int i = 0; i < 4; ++i) {
    const NodeMatrix zi = (1.0 + 0.01 * i) * z + 1e-13 * randomBlock(16 + i);
    history.add(zi, k(zi));
  }
  const NodeMatrix target = 1.5 * z + 0.2 * randomBlock(30);
  const NodeMatrix g = k(target);
  NodeMatrix guess;
  ASSERT_TRUE(history.guess(g, guess));
  ASSERT_TRUE(guess.allFinite());
  // The best multiple of z alone.
  const NodeMatrix kz = k(z);
  const double alpha = (kz.array() * g.array()).sum() / kz.squaredNorm();
  EXPECT_LE((g - k(guess)).norm(), (1.0 + 1e-6) * (g - alpha * kz).norm());
}

}  // namespace
}  // namespace weft
