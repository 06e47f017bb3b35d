#include <weft/collision/ZoneQp.h>

#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::collision {

const char* toString(ZoneQpStop stop) {
  switch (stop) {
    case ZoneQpStop::Optimal:
      return "optimal";
    case ZoneQpStop::Infeasible:
      return "infeasible";
    case ZoneQpStop::IterationCap:
      return "iteration cap";
    case ZoneQpStop::InvalidInput:
      return "invalid input";
  }
  return "unknown";
}

namespace {

bool validQp(const ZoneQp& qp) {
  const Eigen::Index n = qp.x.size();
  if (qp.weights.size() != n || qp.G.cols() != n || qp.G.rows() != qp.h.size()) return false;
  if (!qp.x.allFinite() || !qp.weights.allFinite() || !qp.G.allFinite() || !qp.h.allFinite())
    return false;
  return n == 0 || qp.weights.minCoeff() > 0.0;
}

// (G z + h)_j and its tolerance violationTolerance (|h_j| + sum_k |G_jk z_k|).
void residuals(const ZoneQp& qp, const Eigen::VectorXd& z, double relTol, Eigen::VectorXd& g,
               Eigen::VectorXd& tol) {
  g.noalias() = qp.G * z;
  g += qp.h;
  tol.noalias() = qp.G.cwiseAbs() * z.cwiseAbs();
  tol += qp.h.cwiseAbs();
  tol *= relTol;
}

}  // namespace

ZoneQpSolution solveZoneQp(const ZoneQp& qp, const ZoneQpOptions& options) {
  ZoneQpSolution sol;
  if (!validQp(qp)) {
    sol.stop = ZoneQpStop::InvalidInput;
    return sol;
  }
  const Eigen::Index n = qp.x.size();
  const Eigen::Index m = qp.h.size();
  const int cap =
      options.maxIterations > 0 ? options.maxIterations : static_cast<int>(10 * (m + n) + 10);
  // Goldfarb-Idnani in y = W^{1/2} z, where the objective is 1/2 |y - y0|^2 and row j reads
  // N_j^T y >= b_j with N_j = -W^{-1/2} G_j^T, b_j = h_j (that is, G_j z + h_j <= 0). With the
  // identity Hessian, y = y0 + N_A u_A throughout and u are the multipliers lambda.
  const Eigen::VectorXd sqrtW = qp.weights.cwiseSqrt();
  const Eigen::VectorXd invSqrtW = sqrtW.cwiseInverse();
  const Eigen::MatrixXd N = -(qp.G * invSqrtW.asDiagonal()).transpose();  // n x m
  const Eigen::VectorXd y0 = sqrtW.cwiseProduct(qp.x);
  Eigen::VectorXd y = y0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m);
  std::vector<char> isActive(static_cast<size_t>(m), 0);
  std::vector<int>& active = sol.activeSet;
  active.reserve(static_cast<size_t>(std::min(m, n)));

  Eigen::MatrixXd NA(n, std::min(m, n));
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(n, std::min(m, n));
  Eigen::VectorXd g(m), tol(m), z(n), v(n), dir(n), r(std::min(m, n));
  const double inf = std::numeric_limits<double>::infinity();

  auto factorActive = [&]() {
    const Eigen::Index q = static_cast<Eigen::Index>(active.size());
    for (Eigen::Index i = 0; i < q; ++i) NA.col(i) = N.col(active[static_cast<size_t>(i)]);
    if (q > 0) qr.compute(NA.leftCols(q));
  };
  auto dropActive = [&](size_t k) {
    u[active[k]] = 0.0;
    isActive[static_cast<size_t>(active[k])] = 0;
    active.erase(active.begin() + static_cast<std::ptrdiff_t>(k));
  };

  sol.stop = ZoneQpStop::IterationCap;
  while (true) {
    // Step 1: the most violated constraint outside the active set; none left means optimal.
    z = invSqrtW.cwiseProduct(y);
    residuals(qp, z, options.violationTolerance, g, tol);
    Eigen::Index p = -1;
    double worst = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (isActive[static_cast<size_t>(j)] || g[j] <= tol[j]) continue;
      if (g[j] > worst) {
        worst = g[j];
        p = j;
      }
    }
    if (p < 0) {
      sol.stop = ZoneQpStop::Optimal;
      break;
    }
    // Step 2: move towards satisfying p, dropping blocking constraints, until p is active.
    double uPlus = 0.0;
    bool added = false;
    bool stopped = false;
    const auto np = N.col(p);
    while (!added) {
      if (sol.iterations >= cap) {
        stopped = true;
        sol.stop = ZoneQpStop::IterationCap;
        break;
      }
      ++sol.iterations;
      factorActive();
      const Eigen::Index q = static_cast<Eigen::Index>(active.size());
      // dir: the part of n_p orthogonal to the active normals; r = N_A^+ n_p.
      if (q > 0) {
        v.noalias() = qr.householderQ().adjoint() * np;
        r.head(q) = v.head(q);
        qr.matrixQR().topLeftCorner(q, q).triangularView<Eigen::Upper>().solveInPlace(r.head(q));
        v.head(q).setZero();
        dir.noalias() = qr.householderQ() * v;
      } else {
        dir = np;
      }
      // Partial (dual) step: the largest t keeping every active multiplier u - t r >= 0.
      double t1 = inf;
      Eigen::Index k = -1;
      const double rScale = q > 0 ? r.head(q).cwiseAbs().maxCoeff() : 0.0;
      for (Eigen::Index i = 0; i < q; ++i) {
        if (r[i] <= options.dependenceTolerance * rScale) continue;
        const double ratio = u[active[static_cast<size_t>(i)]] / r[i];
        if (ratio < t1) {
          t1 = ratio;
          k = i;
        }
      }
      // Full (primal) step: the t making constraint p tight along dir.
      double t2 = inf;
      const double dirNorm2 = dir.squaredNorm();
      if (std::sqrt(dirNorm2) > options.dependenceTolerance * np.norm()) {
        const double slack = np.dot(y) - qp.h[p];  // < 0 while p is violated
        t2 = std::max(0.0, -slack / dirNorm2);
      }
      if (t1 == inf && t2 == inf) {
        stopped = true;
        sol.stop = ZoneQpStop::Infeasible;
        break;
      }
      const double t = std::min(t1, t2);
      if (t2 < inf) y.noalias() += t * dir;
      for (Eigen::Index i = 0; i < q; ++i) u[active[static_cast<size_t>(i)]] -= t * r[i];
      uPlus += t;
      if (t2 <= t1) {
        u[p] = uPlus;
        isActive[static_cast<size_t>(p)] = 1;
        active.push_back(static_cast<int>(p));
        added = true;
      } else {
        dropActive(static_cast<size_t>(k));
      }
    }
    if (stopped) break;
  }

  // Polish on the final active set: solve N_A^T N_A u_A = b_A - N_A^T y0 so that the active rows
  // are tight and stationarity (Liang Eq. 10) holds to round-off; kept only if u_A stays >= 0.
  if (sol.stop == ZoneQpStop::Optimal && !active.empty()) {
    factorActive();
    const Eigen::Index q = static_cast<Eigen::Index>(active.size());
    Eigen::VectorXd rhs(q);
    for (Eigen::Index i = 0; i < q; ++i) {
      const int j = active[static_cast<size_t>(i)];
      rhs[i] = qp.h[j] - N.col(j).dot(y0);
    }
    const auto R = qr.matrixQR().topLeftCorner(q, q).triangularView<Eigen::Upper>();
    Eigen::VectorXd uA = R.solve(R.transpose().solve(rhs));
    if (uA.allFinite() && uA.minCoeff() >= 0.0) {
      y = y0;
      for (Eigen::Index i = 0; i < q; ++i) {
        const int j = active[static_cast<size_t>(i)];
        u[j] = uA[i];
        y.noalias() += uA[i] * N.col(j);
      }
    }
  }
  for (Eigen::Index j = 0; j < m; ++j) u[j] = std::max(u[j], 0.0);

  // z from stationarity in the original variables, W (z - x) + G^T lambda = 0: exact where no
  // row binds (z = x bit for bit) and free of the W^{1/2} round trip elsewhere.
  sol.lambda = u;
  sol.z.noalias() = qp.G.transpose() * u;
  sol.z = qp.x - sol.z.cwiseQuotient(qp.weights);
  residuals(qp, sol.z, options.violationTolerance, g, tol);
  sol.maxViolation = m > 0 ? std::max(0.0, g.maxCoeff()) : 0.0;
  sol.converged = sol.stop == ZoneQpStop::Optimal;
  return sol;
}

namespace {

bool validGradientInput(const ZoneQp& qp, const ZoneQpSolution& sol, const Eigen::VectorXd& dLdz) {
  return validQp(qp) && sol.z.size() == qp.x.size() && sol.lambda.size() == qp.h.size() &&
         dLdz.size() == qp.x.size();
}

ZoneQpGradient emptyGradient(const ZoneQp& qp) {
  ZoneQpGradient grad;
  grad.dLdx = Eigen::VectorXd::Zero(qp.x.size());
  grad.dLdG = Eigen::MatrixXd::Zero(qp.G.rows(), qp.G.cols());
  grad.dLdh = Eigen::VectorXd::Zero(qp.h.size());
  grad.dz = Eigen::VectorXd::Zero(qp.x.size());
  grad.lambdaDLambda = Eigen::VectorXd::Zero(qp.h.size());
  grad.lambdaUsed = Eigen::VectorXd::Zero(qp.h.size());
  return grad;
}

// Liang Eqs. 14-16 with the code's convention mu = D(lambda) d_lambda. Derivation (verified by
// central differences in the tests): with the active rows tight, W dz + G^T dlambda =
// W dx - dG^T lambda and G dz = -dG z - dh; for the adjoint pair (a, b) solving W a + G^T b =
// dL/dz, G a = 0, dL = a^T (W dx - dG^T lambda) - b^T (dG z + dh), hence dL/dx = W a,
// dL/dG = -b z^T - lambda a^T, dL/dh = -b. The paper's signs in Eqs. 14-16 agree.
void assembleGradient(const ZoneQp& qp, const ZoneQpSolution& sol, const Eigen::VectorXd& lambda,
                      ZoneQpGradient& grad) {
  grad.dLdx = qp.weights.cwiseProduct(grad.dz);
  grad.dLdG.noalias() = -grad.lambdaDLambda * sol.z.transpose();
  grad.dLdG.noalias() -= lambda * grad.dz.transpose();
  grad.dLdh = -grad.lambdaDLambda;
}

}  // namespace

ZoneQpGradient zoneQpGradientQr(const ZoneQp& qp, const ZoneQpSolution& sol,
                                const Eigen::VectorXd& dLdz, const ZoneQpGradientOptions& options) {
  ZoneQpGradient grad = emptyGradient(qp);
  if (!validGradientInput(qp, sol, dLdz)) return grad;
  const Eigen::Index n = qp.x.size();
  const Eigen::Index m = qp.h.size();
  const Eigen::VectorXd invSqrtW = qp.weights.cwiseSqrt().cwiseInverse();

  // Rows kept: lambda_j > 0 (Liang Sec. 3.4.2), not |G_j z + h_j| <= tol. A row with lambda_j = 0
  // enters Eqs. 15-16 only through D(lambda) d_lambda, which vanishes; keeping a nearly tight
  // but slack row would wrongly project d_z onto its face. Tight rows with lambda_j = 0 are the
  // degenerate (non-differentiable) case; leaving them out gives the derivative of the side
  // where they stay slack. Duplicated and dependent rows are handled by the rank truncation.
  std::vector<int> rows;
  for (Eigen::Index j = 0; j < m; ++j)
    if (sol.lambda[j] > options.lambdaThreshold) rows.push_back(static_cast<int>(j));
  const Eigen::Index q = static_cast<Eigen::Index>(rows.size());
  grad.activeConstraints = static_cast<int>(q);
  const Eigen::VectorXd w = invSqrtW.cwiseProduct(dLdz);  // W^{-1/2} dL/dz
  if (q == 0) {
    grad.dz = invSqrtW.cwiseProduct(w);
    assembleGradient(qp, sol, grad.lambdaUsed, grad);
    grad.ok = true;
    return grad;
  }

  // Liang Eq. 17 with column pivoting: W^{-1/2} G_A^T P = Q R, |R_00| >= |R_11| >= ...
  Eigen::MatrixXd A(n, q);
  for (Eigen::Index i = 0; i < q; ++i)
    A.col(i) = invSqrtW.cwiseProduct(qp.G.row(rows[static_cast<size_t>(i)]).transpose());
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd& QR = qr.matrixQR();
  const Eigen::Index diag = std::min(n, q);
  const double r00 = diag > 0 ? std::abs(QR(0, 0)) : 0.0;
  Eigen::Index k = 0;
  while (k < diag && std::abs(QR(k, k)) > options.rankTolerance * r00 && r00 > 0.0) ++k;
  grad.rank = static_cast<int>(k);
  const auto& perm = qr.colsPermutation().indices();  // column i of A P is column perm[i] of A

  // Liang Eq. 21: W^{-1/2} G_A^T lambda_A = Q_1 (R_1 lambda_1 + R_2 lambda_2)
  //             = Q_1 R_1 (lambda_1 + R_1^{-1} R_2 lambda_2), so the dependent rows' multipliers
  // move onto the independent ones without changing z's stationarity.
  Eigen::VectorXd lambdaP(q);
  for (Eigen::Index i = 0; i < q; ++i) lambdaP[i] = sol.lambda[rows[static_cast<size_t>(perm[i])]];
  const auto R1 = QR.topLeftCorner(k, k).triangularView<Eigen::Upper>();
  Eigen::VectorXd lambda1 = lambdaP.head(k);
  if (k < q) lambda1 += R1.solve(QR.block(0, k, k, q - k) * lambdaP.tail(q - k));

  // Liang Eqs. 18-19 with Q truncated to its first k columns Q_1.
  Eigen::VectorXd v = qr.householderQ().adjoint() * w;  // Q^T W^{-1/2} dL/dz
  const Eigen::VectorXd mu1 = R1.solve(v.head(k));      // D(lambda) d_lambda of kept rows
  v.head(k).setZero();
  const Eigen::VectorXd projected = qr.householderQ() * v;  // (I - Q_1 Q_1^T) W^{-1/2} dL/dz
  grad.dz = invSqrtW.cwiseProduct(projected);
  for (Eigen::Index i = 0; i < k; ++i) {
    const int j = rows[static_cast<size_t>(perm[i])];
    grad.lambdaDLambda[j] = mu1[i];
    grad.lambdaUsed[j] = lambda1[i];
  }
  assembleGradient(qp, sol, grad.lambdaUsed, grad);
  grad.ok = true;
  return grad;
}

ZoneQpGradient zoneQpGradientKkt(const ZoneQp& qp, const ZoneQpSolution& sol,
                                 const Eigen::VectorXd& dLdz) {
  ZoneQpGradient grad = emptyGradient(qp);
  if (!validGradientInput(qp, sol, dLdz)) return grad;
  const Eigen::Index n = qp.x.size();
  const Eigen::Index m = qp.h.size();
  // Liang Eq. 13: [W, G^T D(lambda); G, D(G z + h)] [d_z; d_lambda] = [dL/dz; 0].
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n).diagonal() = qp.weights;
  K.topRightCorner(n, m) = qp.G.transpose() * sol.lambda.asDiagonal();
  K.bottomLeftCorner(m, n) = qp.G;
  Eigen::VectorXd gz = qp.G * sol.z + qp.h;
  K.bottomRightCorner(m, m).diagonal() = gz;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = dLdz;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  lu.setThreshold(1e-12);
  grad.rank = static_cast<int>(lu.rank());
  grad.activeConstraints = static_cast<int>((sol.lambda.array() > 0.0).count());
  if (!lu.isInvertible()) return grad;
  const Eigen::VectorXd d = lu.solve(rhs);
  grad.dz = d.head(n);
  grad.lambdaDLambda = sol.lambda.cwiseProduct(d.tail(m));
  grad.lambdaUsed = sol.lambda;
  assembleGradient(qp, sol, sol.lambda, grad);
  grad.ok = true;
  return grad;
}

}  // namespace weft::collision
