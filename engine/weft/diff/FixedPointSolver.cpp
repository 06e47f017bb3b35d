#include <weft/diff/FixedPointSolver.h>

#include <weft/diff/AdjointSystem.h>

#include <cmath>

namespace weft {

LinearSolveResult FixedPointSolver::solve(AdjointSystem& system, const NodeMatrix& rhs,
                                          NodeMatrix& z) {
  LinearSolveResult result;
  const double rhsNorm = rhs.norm();
  if (rhsNorm == 0.0) {
    z.setZero(rhs.rows(), 3);
    result.converged = true;
    return result;
  }
  deltaPz_.setZero(rhs.rows(), 3);  // Delta P z_0, z_0 = 0
  history_.clear();
  while (result.iterations < maxIterations_) {
    z = deltaPz_ + rhs;  // Eq. 20 / 30: P z_{k+1} = (Delta P + Delta R) z_k + g
    system.solveP(z);
    ++result.iterations;
    if (!system.hasCoupling()) {  // K = P: one solve is exact
      result.residual = 0.0;
      result.converged = true;
      return result;
    }
    system.multiplyCoupling(z, nextDeltaPz_);
    // g - K z_{k+1} = g - P z_{k+1} + (P - K) z_{k+1} = (P - K)(z_{k+1} - z_k).
    result.residual = (nextDeltaPz_ - deltaPz_).norm() / rhsNorm;
    deltaPz_.swap(nextDeltaPz_);
    if (result.residual < tolerance_) {
      result.converged = true;
      return result;
    }
    // Divergence: the residual exceeds the bound, or has grown over the last 2 x kWindow
    // iterations (past the transient the residual shrinks by about rho(P^{-1} Delta P) per
    // iteration, so sustained growth means rho >= 1 and iterating further is wasted).
    history_.push_back(result.residual);
    const std::size_t k = history_.size();
    const bool growing = k > 3 * kWindow && history_[k - 1] > history_[k - 1 - kWindow] &&
                         history_[k - 1 - kWindow] > history_[k - 1 - 2 * kWindow];
    if (!std::isfinite(result.residual) || result.residual > divergenceRatio_ || growing) {
      result.diverged = true;
      return result;
    }
  }
  return result;
}

}  // namespace weft
