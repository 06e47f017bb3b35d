#include <weft/diff/DirectLuSolver.h>

#include <weft/diff/AdjointSystem.h>

#include <Eigen/UmfPackSupport>
#include <cmath>

namespace weft {

LinearSolveResult DirectLuSolver::solve(AdjointSystem& system, const NodeMatrix& rhs,
                                        NodeMatrix& z) {
  LinearSolveResult result;
  const int m = static_cast<int>(rhs.rows());
  // K itself without contact; with contact the augmented system whose first 3m unknowns are z.
  const Eigen::SparseMatrix<double> k = system.assembleSystem();
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(k);
  z.setZero(m, 3);
  if (lu.info() != Eigen::Success) return result;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(k.rows());
  g.head(3 * m) = Eigen::Map<const Eigen::VectorXd>(rhs.data(), 3 * m);
  const Eigen::VectorXd solution = lu.solve(g);
  if (lu.info() != Eigen::Success || !solution.allFinite()) return result;
  Eigen::Map<Eigen::VectorXd>(z.data(), 3 * m) = solution.head(3 * m);
  const double rhsNorm = rhs.norm();
  result.residual = rhsNorm > 0.0 ? (g - k * solution).norm() / rhsNorm : 0.0;
  result.converged = std::isfinite(result.residual);
  return result;
}

}  // namespace weft
