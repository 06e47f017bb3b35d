#include <weft/diff/GmresSolver.h>

#include <weft/diff/AdjointSystem.h>

namespace weft {

LinearSolveResult GmresSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) {
  // Without Delta P the clamped Hessian is P itself.
  const bool hessian =
      preconditioner_ == Preconditioner::ClampedHessian && system.hasDeltaP() && system.factorClampedHessian();
  const GmresResult r = gmres_.solve([&](const NodeMatrix& in, NodeMatrix& out) { system.multiplyK(in, out); },
                                     [&](const NodeMatrix& in, NodeMatrix& out) {
                                       out = in;
                                       if (hessian)
                                         system.solveClampedHessian(out);
                                       else
                                         system.solveP(out);
                                     },
                                     rhs, z, tolerance_, maxIterations_, restart_, warmStart_);
  LinearSolveResult result;
  result.converged = r.converged;
  result.iterations = r.iterations;
  result.residual = r.residual;
  return result;
}

}  // namespace weft
