#pragma once
// The PD system matrix P = M + h^2 sum_i w_i A_i^T A_i (DiffCloth Eq. 7), one coordinate
// (P = this (x) I_3), with its prefactorisation: assembled and factorised once per simulation,
// then multiplied and solved with in every step.

#include <weft/core/Types.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/SparseCholesky.h>

#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace weft {

class SystemMatrix {
 public:
  // Throws NumericalError when P is not positive definite.
  SystemMatrix(const Eigen::VectorXd& mass,
               const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints, double h);

  const Eigen::SparseMatrix<double>& matrix() const { return system_; }
  const SparseCholesky& factor() const { return cholesky_; }
  // out = P in, the three columns at once, rows in parallel.
  void multiply(const NodeMatrix& in, NodeMatrix& out) const;
  // b <- P^-1 b.
  void solveInPlace(NodeMatrix& b) { cholesky_.solveInPlace(b); }

 private:
  Eigen::SparseMatrix<double> system_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows_;  // the same, for row-parallel products
  SparseCholesky cholesky_;
};

}  // namespace weft
