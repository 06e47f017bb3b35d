#include <weft/collision/SparseZoneQp.h>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::collision {

ZoneQp toDense(const SparseZoneQp& qp) {
  ZoneQp dense;
  dense.x = qp.x;
  dense.weights = qp.weights;
  dense.G = Eigen::MatrixXd(qp.G);
  dense.h = qp.h;
  return dense;
}

ZoneQpSolution solveSparseZoneQp(const SparseZoneQp& qp, const ZoneQpOptions& options) {
  using Sparse = Eigen::SparseMatrix<double>;
  ZoneQpSolution out;
  const Eigen::Index n = qp.x.size(), m = qp.h.size();
  out.z = qp.x;
  out.lambda = Eigen::VectorXd::Zero(m);
  if (qp.weights.size() != n || qp.G.rows() != m || qp.G.cols() != n ||
      (qp.weights.array() <= 0.0).any() || !qp.x.allFinite() || !qp.h.allFinite()) {
    out.stop = ZoneQpStop::InvalidInput;
    return out;
  }
  const int cap = options.maxIterations > 0 ? options.maxIterations : 500;
  // The penalty, relative to the problem's scale: rho |G_j|^2 / w against 1.
  double rowNorm = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) rowNorm = std::max(rowNorm, qp.G.row(j).squaredNorm());
  const double rho0 = 1e5 * qp.weights.maxCoeff() / std::max(rowNorm, 1e-300);
  // Continuation: a soft penalty first (few rows change side per Newton step), stiffened tenfold
  // per outer step up to rho0.
  double rho = 1e-4 * rho0, lastViolation = std::numeric_limits<double>::infinity();

  // Row j's satisfaction scale, as in ZoneQpOptions::violationTolerance: |h_j| + sum |G_jk z_k|.
  auto satisfied = [&](const Eigen::VectorXd& z, const Eigen::VectorXd& g) {
    for (Eigen::Index j = 0; j < m; ++j) {
      double scale = std::abs(qp.h[j]);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(qp.G, j); it; ++it)
        scale += std::abs(it.value() * z[it.col()]);
      if (g[j] > options.violationTolerance * scale) return false;
    }
    return true;
  };

  Eigen::VectorXd g = qp.G * out.z + qp.h, rhs(n), gradient(n);
  const Eigen::VectorXd wx = qp.weights.cwiseProduct(qp.x);
  std::vector<char> active(static_cast<std::size_t>(m), 0), next(active.size(), 0);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SimplicialLDLT<Sparse> ldlt;
  Sparse H(n, n);
  int newtonSteps = 0;
  bool capped = false;
  for (int outer = 0; outer < 100 && !capped; ++outer) {
    // Inner: semismooth Newton on the active rows {g_j + lambda_j / rho > 0} with an Armijo line
    // search on the (convex, C^1) inner objective, which keeps the steps from cycling; done when
    // a full step lands on a point with the same active rows (the exact minimiser).
    auto objective = [&](const Eigen::VectorXd& z, const Eigen::VectorXd& gz) {
      double f = 0.5 * (z - qp.x).cwiseAbs2().dot(qp.weights);
      for (Eigen::Index j = 0; j < m; ++j) {
        const double r = std::max(0.0, gz[j] + out.lambda[j] / rho);
        f += 0.5 * rho * r * r;
      }
      return f;
    };
    for (Eigen::Index j = 0; j < m; ++j)
      active[static_cast<std::size_t>(j)] = g[j] + out.lambda[j] / rho > 0.0;
    for (;;) {
      if (++newtonSteps > cap) {
        capped = true;
        break;
      }
      triplets.clear();
      for (Eigen::Index i = 0; i < n; ++i) triplets.emplace_back(i, i, qp.weights[i]);
      rhs = wx;
      gradient = qp.weights.cwiseProduct(out.z - qp.x);
      for (Eigen::Index j = 0; j < m; ++j) {
        if (!active[static_cast<std::size_t>(j)]) continue;
        // rho G_j^T G_j, and -G_j^T (lambda_j + rho h_j).
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator a(qp.G, j); a; ++a) {
          rhs[a.col()] -= a.value() * (out.lambda[j] + rho * qp.h[j]);
          gradient[a.col()] += a.value() * (out.lambda[j] + rho * g[j]);
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator b(qp.G, j); b; ++b)
            triplets.emplace_back(a.col(), b.col(), rho * a.value() * b.value());
        }
      }
      H.setFromTriplets(triplets.begin(), triplets.end());
      ldlt.compute(H);
      if (ldlt.info() != Eigen::Success) {
        out.stop = ZoneQpStop::InvalidInput;
        out.iterations = newtonSteps;
        return out;
      }
      Eigen::VectorXd target = ldlt.solve(rhs);
      target += ldlt.solve(rhs - H * target);  // one step of refinement
      const Eigen::VectorXd step = target - out.z;
      const double slope = gradient.dot(step), f0 = objective(out.z, g);
      double t = 1.0;
      Eigen::VectorXd trial = target, gTrial = qp.G * trial + qp.h;
      for (int halving = 0;
           halving < 40 && slope < 0.0 && objective(trial, gTrial) > f0 + 1e-4 * t * slope;
           ++halving) {
        t *= 0.5;
        trial = out.z + t * step;
        gTrial = qp.G * trial + qp.h;
      }
      out.z = trial;
      g = gTrial;
      bool same = t == 1.0;
      for (Eigen::Index j = 0; j < m; ++j) {
        const std::size_t u = static_cast<std::size_t>(j);
        next[u] = g[j] + out.lambda[j] / rho > 0.0;
        same = same && next[u] == active[u];
      }
      // Rows within round-off of their kink can flip back and forth: a step at the level of
      // round-off ends the inner solve too.
      if (same || step.cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + out.z.cwiseAbs().maxCoeff()) ||
          (t < 1.0 && f0 - objective(out.z, g) <= 1e-14 * std::abs(f0)))
        break;
      active.swap(next);
    }
    // Multiplier update; with the inner solve exact, W (z - x) + G^T lambda = 0 now holds.
    for (Eigen::Index j = 0; j < m; ++j) out.lambda[j] = std::max(0.0, out.lambda[j] + rho * g[j]);
    if (!capped && satisfied(out.z, g)) {
      out.converged = true;
      break;
    }
    // Rows that depend on each other nearly (cloth layers: near-parallel normals) converge at
    // 1 / (1 + rho sigma) with a small sigma: a tenfold larger penalty when an outer step did not
    // shrink the violation tenfold (bounded, so that W + rho G^T G stays factorable).
    const double violation = m > 0 ? std::max(0.0, g.maxCoeff()) : 0.0;
    if (rho < rho0 || (violation > 0.1 * lastViolation && rho < 1e2 * rho0)) rho *= 10.0;
    lastViolation = violation;
  }
  out.iterations = std::min(newtonSteps, cap);
  out.maxViolation = m > 0 ? std::max(0.0, g.maxCoeff()) : 0.0;
  out.activeSet.clear();
  for (Eigen::Index j = 0; j < m; ++j)
    if (out.lambda[j] > 0.0) out.activeSet.push_back(static_cast<int>(j));
  out.stop = out.converged ? ZoneQpStop::Optimal : ZoneQpStop::IterationCap;
  return out;
}

}  // namespace weft::collision
