// The sparse augmented-Lagrangian solve of large impact zones (SparseZoneQp.h) against the dense
// Goldfarb-Idnani solve of ZoneQp.h: the same minimiser and KKT conditions on zone-like QPs
// (rows touching two nodes along nearly parallel normals, as cloth layers make), with
// duplicated rows, and a reported cap.

#include <weft/collision/SparseZoneQp.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace weft::collision {
namespace {

// A zone-like QP: `nodes` nodes, m rows, each pushing node a along a normal near +z against
// node b; about a third of the rows are tight at a common feasible point p.
SparseZoneQp zoneLikeQp(std::mt19937& rng, int nodes, Eigen::Index m, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Index n = 3 * nodes;
  SparseZoneQp qp;
  qp.weights.resize(n);
  for (int i = 0; i < nodes; ++i) qp.weights.segment<3>(3 * i).setConstant(0.3 + std::abs(u(rng)));
  qp.x.resize(n);
  Eigen::VectorXd p(n);
  for (Eigen::Index i = 0; i < n; ++i) qp.x[i] = 0.01 * u(rng), p[i] = 0.01 * u(rng);
  std::vector<Eigen::Triplet<double>> triplets;
  qp.h.resize(m);
  const Eigen::Vector3d base(0.1 * u(rng), 0.1 * u(rng), 1.0);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::Vector3d normal =
        (base + spread * Eigen::Vector3d(u(rng), u(rng), u(rng))).normalized();
    const int a = static_cast<int>(rng() % static_cast<unsigned>(nodes));
    const int b = static_cast<int>(rng() % static_cast<unsigned>(nodes));
    double row = 0.0;
    const double wb = std::abs(u(rng));
    for (int c = 0; c < 3; ++c) {
      triplets.emplace_back(j, 3 * a + c, -normal[c]);
      row -= normal[c] * p[3 * a + c];
      if (b != a) {
        triplets.emplace_back(j, 3 * b + c, wb * normal[c]);
        row += wb * normal[c] * p[3 * b + c];
      }
    }
    qp.h[j] = -row - (rng() % 3 == 0 ? 0.0 : 1e-3 * std::abs(u(rng)));
  }
  qp.G.resize(m, n);
  qp.G.setFromTriplets(triplets.begin(), triplets.end());
  return qp;
}

// Feasibility and complementarity to `tol`; stationarity relative to the displacement's force
// W (z - x): the augmented Lagrangian's multipliers come from its last update, accurate to
// about 1e-5 of it (the minimiser itself matches the dense solve to 1e-10).
void expectKkt(const SparseZoneQp& qp, const ZoneQpSolution& sol, double tol) {
  ASSERT_TRUE(sol.converged) << toString(sol.stop);
  const Eigen::VectorXd force = qp.weights.cwiseProduct(sol.z - qp.x);
  const Eigen::VectorXd stationarity = force + qp.G.transpose() * sol.lambda;
  EXPECT_LE(stationarity.cwiseAbs().maxCoeff(), 1e-4 * force.cwiseAbs().maxCoeff() + tol);
  const Eigen::VectorXd g = qp.G * sol.z + qp.h;
  EXPECT_LE(g.maxCoeff(), tol);
  EXPECT_GE(sol.lambda.minCoeff(), 0.0);
  EXPECT_LE(sol.lambda.cwiseProduct(g).cwiseAbs().maxCoeff(), tol);
}

TEST(CollisionSparseZoneQp, EqualsTheDenseSolveOnZoneLikeQps) {
  std::mt19937 rng(7);
  int worstIterations = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int nodes = 4 + static_cast<int>(rng() % 40);
    const Eigen::Index m = 1 + static_cast<Eigen::Index>(rng() % static_cast<unsigned>(4 * nodes));
    const double spread = std::pow(10.0, -1.0 - static_cast<double>(rng() % 4));
    const SparseZoneQp qp = zoneLikeQp(rng, nodes, m, spread);
    const ZoneQpSolution sparse = solveSparseZoneQp(qp);
    const ZoneQpSolution dense = solveZoneQp(toDense(qp));
    ASSERT_TRUE(dense.converged);
    SCOPED_TRACE(trial);
    expectKkt(qp, sparse, 1e-10);
    // The minimiser is unique (W > 0); the multipliers need not be (dependent rows).
    EXPECT_LE((sparse.z - dense.z).cwiseAbs().maxCoeff(), 1e-10);
    worstIterations = std::max(worstIterations, sparse.iterations);
  }
  std::printf("largest Newton step count: %d\n", worstIterations);
}

TEST(CollisionSparseZoneQp, DuplicatedRowsGiveTheSameMinimiser) {
  std::mt19937 rng(19);
  for (int trial = 0; trial < 50; ++trial) {
    const SparseZoneQp qp = zoneLikeQp(rng, 12, 30, 1e-2);
    SparseZoneQp twice = qp;
    const Eigen::Index m = qp.h.size(), n = qp.x.size();
    Eigen::MatrixXd G(2 * m, n);
    G << Eigen::MatrixXd(qp.G), Eigen::MatrixXd(qp.G);
    twice.G = G.sparseView();
    twice.h.resize(2 * m);
    twice.h << qp.h, qp.h;
    const ZoneQpSolution a = solveSparseZoneQp(qp), b = solveSparseZoneQp(twice);
    ASSERT_TRUE(a.converged && b.converged);
    EXPECT_LE((a.z - b.z).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(CollisionSparseZoneQp, ALargeZoneIsSolved) {
  // 600 nodes and 1,500 rows, the size of cloth layers resting on each other.
  std::mt19937 rng(23);
  const SparseZoneQp qp = zoneLikeQp(rng, 600, 1500, 1e-2);
  const ZoneQpSolution sol = solveSparseZoneQp(qp);
  expectKkt(qp, sol, 1e-10);
  std::printf("1500 rows: %d Newton steps, %zu rows active\n", sol.iterations,
              sol.activeSet.size());
}

TEST(CollisionSparseZoneQp, TheCapAndBadInputAreReported) {
  std::mt19937 rng(29);
  const SparseZoneQp qp = zoneLikeQp(rng, 30, 90, 1e-2);
  const ZoneQpSolution full = solveSparseZoneQp(qp);
  ASSERT_TRUE(full.converged);
  ASSERT_GT(full.iterations, 1);  // (the initial guess of the free set is not the answer)
  ZoneQpOptions o;
  o.maxIterations = 1;
  const ZoneQpSolution capped = solveSparseZoneQp(qp, o);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.stop, ZoneQpStop::IterationCap);
  EXPECT_EQ(capped.iterations, 1);
  SparseZoneQp bad = qp;
  bad.weights[0] = 0.0;
  const ZoneQpSolution invalid = solveSparseZoneQp(bad);
  EXPECT_FALSE(invalid.converged);
  EXPECT_EQ(invalid.stop, ZoneQpStop::InvalidInput);
}

}  // namespace
}  // namespace weft::collision
