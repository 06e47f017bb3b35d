#include <weft/diff/GmresSolver.h>

#include <weft/diff/AdjointSystem.h>

#include <Eigen/Dense>
#include <cmath>

namespace weft {

LinearSolveResult GmresSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) {
  LinearSolveResult result;
  const int m = static_cast<int>(rhs.rows());
  const double rhsNorm = rhs.norm();
  z.setZero(m, 3);
  if (rhsNorm == 0.0) {
    result.converged = true;
    return result;
  }
  const int restart = std::max(1, restart_);
  if (static_cast<int>(basis_.size()) < restart + 1) {
    basis_.resize(restart + 1);
    preconditioned_.resize(restart);
  }
  residual_ = rhs;  // g - K z_0 with z_0 = 0
  double residualNorm = rhsNorm;
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(restart + 1, restart);
  Eigen::VectorXd cs(restart), sn(restart), s(restart + 1);
  while (result.iterations < maxIterations_) {
    basis_[0] = residual_ / residualNorm;
    s.setZero();
    s[0] = residualNorm;
    h.setZero();
    int j = 0;
    bool done = false;
    for (; j < restart && result.iterations < maxIterations_; ++j) {
      preconditioned_[j] = basis_[j];
      system.solveP(preconditioned_[j]);
      system.multiplyK(preconditioned_[j], work_);
      ++result.iterations;
      // Modified Gram-Schmidt against the basis.
      for (int i = 0; i <= j; ++i) {
        h(i, j) = blockDot(work_, basis_[i]);
        work_ -= h(i, j) * basis_[i];
      }
      h(j + 1, j) = work_.norm();
      const bool breakdown = !(h(j + 1, j) > 1e-14 * std::abs(h(j, j)) + 1e-300);
      if (!breakdown) basis_[j + 1] = work_ / h(j + 1, j);
      // Apply the previous Givens rotations to column j, then one that zeroes h(j+1, j).
      for (int i = 0; i < j; ++i) {
        const double a = h(i, j), b = h(i + 1, j);
        h(i, j) = cs[i] * a + sn[i] * b;
        h(i + 1, j) = -sn[i] * a + cs[i] * b;
      }
      const double a = h(j, j), b = h(j + 1, j);
      const double r = std::hypot(a, b);
      cs[j] = r > 0.0 ? a / r : 1.0;
      sn[j] = r > 0.0 ? b / r : 0.0;
      h(j, j) = r;
      h(j + 1, j) = 0.0;
      s[j + 1] = -sn[j] * s[j];
      s[j] = cs[j] * s[j];
      if (std::abs(s[j + 1]) < tolerance_ * rhsNorm || breakdown) {
        ++j;
        done = true;
        break;
      }
    }
    // z += P^{-1} V y with H y = s (upper triangular, j columns).
    if (j > 0) {
      const Eigen::VectorXd y =
          h.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(s.head(j));
      for (int i = 0; i < j; ++i) z += y[i] * preconditioned_[i];
    }
    // The true residual decides (the recurrence's estimate drifts in round-off).
    system.multiplyK(z, work_);
    residual_ = rhs - work_;
    const double previous = residualNorm;
    residualNorm = residual_.norm();
    result.residual = residualNorm / rhsNorm;
    if (!std::isfinite(result.residual)) return result;
    if (result.residual < tolerance_) {
      result.converged = true;
      return result;
    }
    if (done && !(residualNorm < 0.5 * previous)) return result;  // stagnated at breakdown
  }
  return result;
}

}  // namespace weft
