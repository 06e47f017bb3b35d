// One impact zone's QP (Liang et al. 2019 Eqs. 8-9) and its gradients (Eqs. 13-21): the
// Goldfarb-Idnani solve against the closed-form projection and the KKT conditions, with
// duplicated and dependent rows and an infeasible set; the QR route against the full KKT
// system of Eq. 13 and both against central differences of L = c^T z.

#include <weft/collision/ZoneQp.h>

#include <gtest/gtest.h>

#include <random>

namespace weft::collision {
namespace {

Eigen::VectorXd randomVector(std::mt19937& rng, Eigen::Index n, double lo, double hi) {
  std::uniform_real_distribution<double> dist(lo, hi);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = dist(rng);
  return v;
}

// A feasible QP whose target x violates many rows: h = -G p - c with c > 0 makes p strictly
// feasible, and x is drawn away from p.
ZoneQp randomQp(std::mt19937& rng, Eigen::Index n, Eigen::Index m) {
  ZoneQp qp;
  qp.weights = randomVector(rng, n, 0.5, 2.0);
  qp.G.resize(m, n);
  for (Eigen::Index j = 0; j < m; ++j) qp.G.row(j) = randomVector(rng, n, -1.0, 1.0).transpose();
  const Eigen::VectorXd p = randomVector(rng, n, -0.5, 0.5);
  qp.h = -qp.G * p - randomVector(rng, m, 0.05, 0.5);
  qp.x = p + randomVector(rng, n, -2.0, 2.0);
  return qp;
}

double loss(const ZoneQp& qp, const Eigen::VectorXd& c) {
  const ZoneQpSolution sol = solveZoneQp(qp);
  EXPECT_TRUE(sol.converged);
  return c.dot(sol.z);
}

void expectKkt(const ZoneQp& qp, const ZoneQpSolution& sol, double tol) {
  ASSERT_TRUE(sol.converged) << toString(sol.stop);
  const Eigen::VectorXd stationarity =
      qp.weights.cwiseProduct(sol.z - qp.x) + qp.G.transpose() * sol.lambda;
  EXPECT_LE(stationarity.cwiseAbs().maxCoeff(), tol);
  const Eigen::VectorXd g = qp.G * sol.z + qp.h;
  EXPECT_LE(g.maxCoeff(), tol);
  EXPECT_GE(sol.lambda.minCoeff(), 0.0);
  EXPECT_LE(sol.lambda.cwiseProduct(g).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE(sol.maxViolation, tol);
}

// No row is degenerate: each is clearly active (lambda > margin) or clearly slack.
bool strictlyComplementary(const ZoneQp& qp, const ZoneQpSolution& sol, double margin) {
  const Eigen::VectorXd g = qp.G * sol.z + qp.h;
  for (Eigen::Index j = 0; j < g.size(); ++j)
    if (!(sol.lambda[j] > margin || g[j] < -margin)) return false;
  return true;
}

double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

TEST(CollisionZoneQp, SingleConstraintIsTheClosedFormProjection) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    ZoneQp qp;
    qp.weights = randomVector(rng, 6, 0.2, 5.0);
    qp.x = randomVector(rng, 6, -1.0, 1.0);
    qp.G = randomVector(rng, 6, -1.0, 1.0).transpose();
    const double gx = qp.G.row(0).dot(qp.x);
    // Alternate violated (g x + h > 0) and satisfied targets.
    qp.h = Eigen::VectorXd::Constant(1, trial % 2 == 0 ? -gx + 0.3 : -gx - 0.3);
    const ZoneQpSolution sol = solveZoneQp(qp);
    ASSERT_TRUE(sol.converged);
    const Eigen::VectorXd winvg = qp.G.row(0).transpose().cwiseQuotient(qp.weights);
    Eigen::VectorXd expected = qp.x;
    if (trial % 2 == 0) expected -= winvg * (gx + qp.h[0]) / qp.G.row(0).dot(winvg);
    EXPECT_LE((sol.z - expected).cwiseAbs().maxCoeff(), 1e-14) << trial;
    if (trial % 2 == 1) {
      EXPECT_EQ(sol.z, qp.x);
      EXPECT_EQ(sol.lambda[0], 0.0);
      EXPECT_EQ(sol.iterations, 0);
    } else {
      EXPECT_GT(sol.lambda[0], 0.0);
      EXPECT_EQ(sol.iterations, 1);
    }
  }
}

TEST(CollisionZoneQp, RandomQpsSatisfyKkt) {
  std::mt19937 rng(11);
  int withSeveralActive = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_int_distribution<int> nodes(1, 5), rows(1, 12);
    const Eigen::Index n = 3 * nodes(rng);
    const ZoneQp qp = randomQp(rng, n, rows(rng));
    const ZoneQpSolution sol = solveZoneQp(qp);
    expectKkt(qp, sol, 1e-10);
    if (sol.activeSet.size() >= 3) ++withSeveralActive;
  }
  EXPECT_GE(withSeveralActive, 50);
}

TEST(CollisionZoneQp, DuplicatedAndDependentRowsGiveTheSameMinimiser) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const ZoneQp qp = randomQp(rng, 9, 4);
    const ZoneQpSolution base = solveZoneQp(qp);
    ASSERT_TRUE(base.converged);
    // Rows 4, 5: exact duplicates of rows 0 and 1; row 6: 2 x row 2; row 7: a nonnegative
    // combination of rows 0 and 3, implied by them. G has rank 4 with 8 rows.
    ZoneQp dup = qp;
    dup.G.conservativeResize(8, Eigen::NoChange);
    dup.h.conservativeResize(8);
    dup.G.row(4) = qp.G.row(0);
    dup.h[4] = qp.h[0];
    dup.G.row(5) = qp.G.row(1);
    dup.h[5] = qp.h[1];
    dup.G.row(6) = 2.0 * qp.G.row(2);
    dup.h[6] = 2.0 * qp.h[2];
    dup.G.row(7) = 0.7 * qp.G.row(0) + 0.4 * qp.G.row(3);
    dup.h[7] = 0.7 * qp.h[0] + 0.4 * qp.h[3];
    const ZoneQpSolution sol = solveZoneQp(dup);
    expectKkt(dup, sol, 1e-10);
    EXPECT_LE((sol.z - base.z).cwiseAbs().maxCoeff(), 1e-10) << trial;
  }
}

// Zone-like QPs: rows -n^T at one node (against a fixed face) or -n^T, +s n^T at two nodes,
// with normals within 10^-1 ... 10^-10 of one another, up to three times more rows than
// variables, and h placing a known point p on or inside every row (so feasible, often
// degenerate). Every solve must converge and satisfy KKT.
TEST(CollisionZoneQp, NearlyParallelRowsConverge) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int maxIterations = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int nodes = 2 + static_cast<int>(rng() % 8);
    const Eigen::Index n = 3 * nodes;
    const Eigen::Index m = 1 + static_cast<Eigen::Index>(rng() % static_cast<unsigned>(3 * n));
    ZoneQp qp;
    qp.weights.resize(n);
    for (int i = 0; i < nodes; ++i)
      qp.weights.segment<3>(3 * i).setConstant(0.3 + std::abs(u(rng)));
    qp.x = 0.01 * randomVector(rng, n, -1.0, 1.0);
    const Eigen::VectorXd p = 0.01 * randomVector(rng, n, -1.0, 1.0);
    const Eigen::Vector3d base = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 1.0).normalized();
    const double spread = std::pow(10.0, -1.0 - static_cast<double>(rng() % 10));
    qp.G.setZero(m, n);
    qp.h.resize(m);
    for (Eigen::Index j = 0; j < m; ++j) {
      const Eigen::Vector3d normal =
          (base + spread * Eigen::Vector3d(u(rng), u(rng), u(rng))).normalized();
      const int a = static_cast<int>(rng() % static_cast<unsigned>(nodes));
      const int b = static_cast<int>(rng() % static_cast<unsigned>(nodes));
      qp.G.block<1, 3>(j, 3 * a) -= normal.transpose();
      if (b != a) qp.G.block<1, 3>(j, 3 * b) += std::abs(u(rng)) * normal.transpose();
      qp.h[j] = -qp.G.row(j).dot(p) - (rng() % 3 == 0 ? 0.0 : 1e-3 * std::abs(u(rng)));
    }
    const ZoneQpSolution sol = solveZoneQp(qp);
    expectKkt(qp, sol, 1e-10);
    maxIterations = std::max(maxIterations, sol.iterations);
  }
  EXPECT_LE(maxIterations, 100);
}

TEST(CollisionZoneQp, InfeasibleQpIsReported) {
  // z_0 >= 1 and z_0 <= 0 (one node, three coordinates).
  ZoneQp qp;
  qp.x = Eigen::Vector3d(0.5, 0.0, 0.0);
  qp.weights = Eigen::Vector3d::Ones();
  qp.G.setZero(2, 3);
  qp.G(0, 0) = -1.0;
  qp.h.resize(2);
  qp.h[0] = 1.0;
  qp.G(1, 0) = 1.0;
  qp.h[1] = 0.0;
  ZoneQpSolution sol = solveZoneQp(qp);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.stop, ZoneQpStop::Infeasible);
  EXPECT_GT(sol.maxViolation, 0.0);

  // Three half-planes of the (z_0, z_1) plane with an empty intersection, none parallel.
  ZoneQp tri;
  tri.x = Eigen::VectorXd::Zero(6);
  tri.weights = Eigen::VectorXd::Constant(6, 2.0);
  tri.G.setZero(3, 6);
  tri.h.resize(3);
  tri.G.row(0).head(2) << -1.0, 0.0;  // z_0 >= 1
  tri.h[0] = 1.0;
  tri.G.row(1).head(2) << 0.0, -1.0;  // z_1 >= 1
  tri.h[1] = 1.0;
  tri.G.row(2).head(2) << 1.0, 1.0;  // z_0 + z_1 <= 1
  tri.h[2] = -1.0;
  sol = solveZoneQp(tri);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.stop, ZoneQpStop::Infeasible);
}

TEST(CollisionZoneQp, IterationCapAndInvalidInputAreReported) {
  std::mt19937 rng(2);
  ZoneQp qp = randomQp(rng, 12, 8);
  ZoneQpOptions options;
  options.maxIterations = 1;
  const ZoneQpSolution full = solveZoneQp(qp);
  ASSERT_TRUE(full.converged);
  ASSERT_GT(full.iterations, 1);
  ZoneQpSolution sol = solveZoneQp(qp, options);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.stop, ZoneQpStop::IterationCap);
  EXPECT_EQ(sol.iterations, 1);

  qp.weights[3] = 0.0;
  sol = solveZoneQp(qp);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.stop, ZoneQpStop::InvalidInput);
}

TEST(CollisionZoneQp, QrGradientEqualsKktGradient) {
  std::mt19937 rng(17);
  int compared = 0;
  for (int trial = 0; trial < 200 && compared < 60; ++trial) {
    std::uniform_int_distribution<int> nodes(2, 5), rows(3, 10);
    const ZoneQp qp = randomQp(rng, 3 * nodes(rng), rows(rng));
    const ZoneQpSolution sol = solveZoneQp(qp);
    ASSERT_TRUE(sol.converged);
    if (sol.activeSet.size() < 2 || !strictlyComplementary(qp, sol, 1e-6)) continue;
    ++compared;
    const Eigen::VectorXd dLdz = randomVector(rng, qp.x.size(), -1.0, 1.0);
    const ZoneQpGradient qr = zoneQpGradientQr(qp, sol, dLdz);
    const ZoneQpGradient kkt = zoneQpGradientKkt(qp, sol, dLdz);
    ASSERT_TRUE(qr.ok);
    ASSERT_TRUE(kkt.ok);
    EXPECT_EQ(qr.rank, qr.activeConstraints);
    EXPECT_LE(relativeError(qr.dLdx, kkt.dLdx), 1e-10) << trial;
    EXPECT_LE(relativeError(qr.dLdG, kkt.dLdG), 1e-10) << trial;
    EXPECT_LE(relativeError(qr.dLdh, kkt.dLdh), 1e-10) << trial;
  }
  EXPECT_GE(compared, 30);
}

// Central differences of L = c^T z(x, G, h) in every entry of x, G and h.
void expectMatchesCentralDifferences(const ZoneQp& qp, const Eigen::VectorXd& c,
                                     const ZoneQpGradient& grad, double tol) {
  const double eps = 1e-6;
  for (Eigen::Index i = 0; i < qp.x.size(); ++i) {
    ZoneQp plus = qp, minus = qp;
    plus.x[i] += eps;
    minus.x[i] -= eps;
    EXPECT_NEAR(grad.dLdx[i], (loss(plus, c) - loss(minus, c)) / (2 * eps), tol) << "x " << i;
  }
  for (Eigen::Index j = 0; j < qp.h.size(); ++j) {
    ZoneQp plus = qp, minus = qp;
    plus.h[j] += eps;
    minus.h[j] -= eps;
    EXPECT_NEAR(grad.dLdh[j], (loss(plus, c) - loss(minus, c)) / (2 * eps), tol) << "h " << j;
    for (Eigen::Index i = 0; i < qp.x.size(); ++i) {
      ZoneQp gp = qp, gm = qp;
      gp.G(j, i) += eps;
      gm.G(j, i) -= eps;
      EXPECT_NEAR(grad.dLdG(j, i), (loss(gp, c) - loss(gm, c)) / (2 * eps), tol)
          << "G " << j << "," << i;
    }
  }
}

TEST(CollisionZoneQp, GradientsMatchCentralDifferences) {
  std::mt19937 rng(23);
  int compared = 0;
  for (int trial = 0; trial < 100 && compared < 10; ++trial) {
    const ZoneQp qp = randomQp(rng, 9, 6);
    const ZoneQpSolution sol = solveZoneQp(qp);
    ASSERT_TRUE(sol.converged);
    // Away from activity changes: a perturbation of 1e-6 must not flip any row.
    if (sol.activeSet.size() < 2 || !strictlyComplementary(qp, sol, 1e-3)) continue;
    ++compared;
    const Eigen::VectorXd c = randomVector(rng, 9, -1.0, 1.0);
    expectMatchesCentralDifferences(qp, c, zoneQpGradientQr(qp, sol, c), 1e-7);
    expectMatchesCentralDifferences(qp, c, zoneQpGradientKkt(qp, sol, c), 1e-7);
  }
  EXPECT_GE(compared, 5);
}

// Rank-deficient active rows: row 3 = row 0 + row 1 (and h likewise), all three tight. The KKT
// matrix of Eq. 13 is singular there, and z(G, h) is not differentiable in directions that
// break the dependency (h_3 alone moved up makes row 3 bind, moved down makes it slack). So the
// QR route (with the transfer of Eq. 21) is checked against central differences in x, and in
// (G, h) along directions that keep row 3 = row 0 + row 1.
TEST(CollisionZoneQp, RankDeficientGradientMatchesCentralDifferences) {
  std::mt19937 rng(29);
  int compared = 0;
  for (int trial = 0; trial < 200 && compared < 10; ++trial) {
    ZoneQp qp = randomQp(rng, 9, 3);
    qp.G.conservativeResize(4, Eigen::NoChange);
    qp.h.conservativeResize(4);
    qp.G.row(3) = qp.G.row(0) + qp.G.row(1);
    qp.h[3] = qp.h[0] + qp.h[1];
    ZoneQpSolution sol = solveZoneQp(qp);
    ASSERT_TRUE(sol.converged);
    const Eigen::VectorXd g = qp.G * sol.z + qp.h;
    // Rows 0 and 1 clearly active, hence row 3 tight too; row 2 clearly active or slack.
    if (!(sol.lambda[0] + sol.lambda[3] > 1e-3 && sol.lambda[1] + sol.lambda[3] > 1e-3 &&
          std::abs(g[0]) < 1e-12 && std::abs(g[1]) < 1e-12 &&
          (sol.lambda[2] > 1e-3 || g[2] < -1e-3)))
      continue;
    ++compared;
    // Redistribute the multipliers of rows 0, 1, 3 so that all three are positive: lambda_0 - s,
    // lambda_1 - s, lambda_3 + s is still a KKT point (same z) for s in [-lambda_3,
    // min(lambda_0, lambda_1)]. The gradients must not change: Eq. 21 moves them back.
    const double s = 0.5 * (std::min(sol.lambda[0], sol.lambda[1]) - sol.lambda[3]);
    ZoneQpSolution shifted = sol;
    shifted.lambda[0] -= s;
    shifted.lambda[1] -= s;
    shifted.lambda[3] += s;
    ASSERT_GT(shifted.lambda.head(2).minCoeff(), 0.0);
    ASSERT_GT(shifted.lambda[3], 0.0);
    const Eigen::VectorXd c = randomVector(rng, 9, -1.0, 1.0);
    const ZoneQpGradient grad = zoneQpGradientQr(qp, sol, c);
    const ZoneQpGradient gradShifted = zoneQpGradientQr(qp, shifted, c);
    ASSERT_TRUE(grad.ok);
    ASSERT_TRUE(gradShifted.ok);
    EXPECT_EQ(gradShifted.rank, gradShifted.activeConstraints - 1);  // one row truncated
    EXPECT_LE(relativeError(gradShifted.dLdx, grad.dLdx), 1e-10);
    // Per row, dL/dG and dL/dh depend on which of the dependent rows carry the transferred
    // multipliers; along directions keeping row 3 = row 0 + row 1 they agree (checked below).
    EXPECT_FALSE(zoneQpGradientKkt(qp, shifted, c).ok);  // Eq. 13 is singular here

    const double eps = 1e-6;
    for (Eigen::Index i = 0; i < 9; ++i) {
      ZoneQp plus = qp, minus = qp;
      plus.x[i] += eps;
      minus.x[i] -= eps;
      EXPECT_NEAR(gradShifted.dLdx[i], (loss(plus, c) - loss(minus, c)) / (2 * eps), 1e-7);
    }
    for (int direction = 0; direction < 5; ++direction) {
      Eigen::MatrixXd dG = Eigen::MatrixXd::Zero(4, 9);
      Eigen::VectorXd dh = Eigen::VectorXd::Zero(4);
      for (int j = 0; j < 3; ++j) {
        dG.row(j) = randomVector(rng, 9, -1.0, 1.0).transpose();
        dh[j] = randomVector(rng, 1, -1.0, 1.0)[0];
      }
      dG.row(3) = dG.row(0) + dG.row(1);
      dh[3] = dh[0] + dh[1];
      ZoneQp plus = qp, minus = qp;
      plus.G += eps * dG;
      plus.h += eps * dh;
      minus.G -= eps * dG;
      minus.h -= eps * dh;
      const double fd = (loss(plus, c) - loss(minus, c)) / (2 * eps);
      for (const ZoneQpGradient* g : {&grad, &gradShifted}) {
        const double predicted = g->dLdG.cwiseProduct(dG).sum() + g->dLdh.dot(dh);
        EXPECT_NEAR(predicted, fd, 1e-7) << trial << " direction " << direction;
      }
    }
  }
  EXPECT_GE(compared, 5);
}

TEST(CollisionZoneQp, NoActiveRowPassesTheGradientThrough) {
  std::mt19937 rng(31);
  ZoneQp qp = randomQp(rng, 6, 3);
  qp.h = -qp.G * qp.x - Eigen::VectorXd::Constant(3, 0.1);  // x itself is strictly feasible
  const ZoneQpSolution sol = solveZoneQp(qp);
  ASSERT_TRUE(sol.converged);
  EXPECT_EQ(sol.z, qp.x);
  const Eigen::VectorXd c = randomVector(rng, 6, -1.0, 1.0);
  for (const ZoneQpGradient& grad : {zoneQpGradientQr(qp, sol, c), zoneQpGradientKkt(qp, sol, c)}) {
    ASSERT_TRUE(grad.ok);
    EXPECT_LE((grad.dLdx - c).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LE(grad.dLdG.cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LE(grad.dLdh.cwiseAbs().maxCoeff(), 1e-14);
  }
}

}  // namespace
}  // namespace weft::collision
