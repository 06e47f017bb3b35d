#pragma once
// Restarted GMRES on K z = g, right-preconditioned by the prefactorised P: it builds a Krylov
// space of K P^{-1} (one back-substitution with P's CHOLMOD factor and one product with K per
// iteration) and minimises the true residual |g - K z| over it. This goes beyond DiffCloth
// (its Sec. 7 names the fixed-point iteration's divergence as a limitation): GMRES converges
// whenever K is non-singular, whatever the spectral radius of P^{-1} Delta P.
//
// Why GMRES and not MINRES: without contact K = P - Delta P is symmetric (indefinite on
// compressed cloth), where preconditioned MINRES would be cheaper per iteration; but contact adds
// Delta R (Eq. 29), which is not symmetric (slip blocks), and the same solver must then work on
// P - Delta P - Delta R. Right preconditioning keeps the monitored residual the true one, so the
// tolerance means the same as for the other two solvers.
//
// Two preconditioners: P's factor (Preconditioner::P, DiffCloth's choice: free, but on a cloth
// in tension a poor model of K) or a fresh factor of the clamped Hessian H each step
// (Preconditioner::ClampedHessian, AdjointSystem::factorClampedHessian: one sparse Cholesky of
// 3m unknowns per step, then a handful of iterations). Each step starts from the previous
// step's z when warmStart is set (the adjoint varies smoothly along the trajectory).

#include <weft/diff/AdjointLinearSolver.h>
#include <weft/physics/Gmres.h>

namespace weft {

class GmresSolver final : public AdjointLinearSolver {
 public:
  enum class Preconditioner { P, ClampedHessian };
  GmresSolver(double tolerance, int maxIterations, int restart = 50, bool warmStart = false,
              Preconditioner preconditioner = Preconditioner::P)
      : tolerance_(tolerance),
        maxIterations_(maxIterations),
        restart_(restart),
        warmStart_(warmStart),
        preconditioner_(preconditioner) {}
  const char* name() const override { return preconditioner_ == Preconditioner::P ? "gmres" : "gmres (hessian)"; }
  LinearSolveResult solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) override;

 private:
  double tolerance_;
  int maxIterations_;
  int restart_;
  bool warmStart_;
  Preconditioner preconditioner_;
  Gmres gmres_;
};

}  // namespace weft
