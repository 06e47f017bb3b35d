#include <weft/diff/DirectLuSolver.h>

#include <weft/diff/AdjointSystem.h>

#include <Eigen/UmfPackSupport>
#include <cmath>

namespace weft {

LinearSolveResult DirectLuSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) {
  LinearSolveResult result;
  const int m = static_cast<int>(rhs.rows());
  const Eigen::SparseMatrix<double> k = system.assembleK();
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(k);
  z.setZero(m, 3);
  if (lu.info() != Eigen::Success) return result;
  const Eigen::Map<const Eigen::VectorXd> g(rhs.data(), 3 * m);
  Eigen::Map<Eigen::VectorXd> flat(z.data(), 3 * m);
  flat = lu.solve(g);
  if (lu.info() != Eigen::Success || !z.allFinite()) return result;
  const double rhsNorm = rhs.norm();
  result.residual = rhsNorm > 0.0 ? (g - k * flat).norm() / rhsNorm : 0.0;
  result.converged = std::isfinite(result.residual);
  return result;
}

}  // namespace weft
