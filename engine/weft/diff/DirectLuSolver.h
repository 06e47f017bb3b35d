#pragma once
// The direct fallback of DiffCloth Sec. 4.2 ("we switch back to a direct sparse matrix solver to
// solve Eqn. (29)"): K assembled explicitly (AdjointSystem::assembleK) and factorised by
// UMFPACK's sparse LU (SuiteSparse, through Eigen's UmfPackSupport). LU rather than Cholesky
// because K is indefinite on compressed cloth, and unsymmetric once contact adds Delta R.
// Costs a factorisation per step: the robust, slow reference the iterative solvers are checked
// against.

#include <weft/diff/AdjointLinearSolver.h>

namespace weft {

class DirectLuSolver final : public AdjointLinearSolver {
 public:
  const char* name() const override { return "direct"; }
  // converged = false if K is numerically singular or the solution is not finite.
  LinearSolveResult solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) override;
};

}  // namespace weft
