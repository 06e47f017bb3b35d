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
// 3m unknowns per step, then a handful of iterations), or Preconditioner::Automatic, which picks
// one per step: P is right where contacts pin the cloth's soft out-of-plane modes or the cloth
// is slack (Slope), the Hessian where the cloth hangs free in tension (Wind), and the
// factorisation costs many iterations with P (AdjointSystem::hessianFactorCost). A step
// first runs with P for as many iterations as a factorisation costs divided by the steps a
// factor serves (counted in the pass, from a prior of kAutomaticPriorReuse; at least
// kAutomaticPIterations); if P has not converged by then, the Hessian is factored and the solve
// continues from where P left it (the ski-rental rule). If the Hessian then converged within
// kAutomaticPIterations more, the following steps start with it (a backward pass walks one
// trajectory, whose stiffness changes slowly), its factor kept until a solve needs more than
// kAutomaticRefactor iterations, probing P again every kAutomaticReprobe steps (for as many
// iterations as the run's steps have cost on average, at least kAutomaticPIterations: a
// factorisation by hessianFactorCost, an iteration with H by hessianIterationCost) and
// staying with P if it converged within them, and dropping back to P as soon as a fresh factor
// needs more than kAutomaticPIterations (such iterations come from the contact part Delta R,
// which neither factor models beyond the contact-prescribed velocities that
// AdjointSystem::precondition inverts exactly around either factor).
// The choice depends on iteration and operation counts only, so repeated runs stay
// bit-identical.
// With warmStart each step starts from the previous step's solution, or with history > 0 from
// the best combination of the last `history` solutions (SolutionHistory; the adjoint varies
// smoothly along the trajectory), and then takes at least kHistoryMinimumIterations
// iterations: such a guess can meet the tolerance without resolving what is new in the step's
// right-hand side (the loss's own term at that step), and the parts left out add up coherently
// over the pass (docs/how-it-works/backward.md, "Measured on the way").

#include <weft/diff/AdjointLinearSolver.h>
#include <weft/diff/SolutionHistory.h>
#include <weft/physics/Gmres.h>

namespace weft {

class GmresSolver final : public AdjointLinearSolver {
 public:
  enum class Preconditioner { P, ClampedHessian, Automatic };
  // Automatic: the fewest iterations with P after which a step switches to the clamped Hessian
  // (and the most when a run of Hessian steps probes P again), and the steps after which such
  // a run tries P again.
  static constexpr int kAutomaticPIterations = 12;
  static constexpr int kAutomaticReprobe = 10;
  // Automatic: iterations with a kept Hessian factor beyond which the next step refactors.
  static constexpr int kAutomaticRefactor = 6;
  // Automatic: the steps a factor is assumed to serve before any has (a prior of 1 keeps P too
  // long on a cloth in tension: docs/how-it-works/backward.md).
  static constexpr int kAutomaticPriorReuse = 2;
  GmresSolver(double tolerance, int maxIterations, int restart = 50, bool warmStart = false,
              Preconditioner preconditioner = Preconditioner::P, int history = 0)
      : tolerance_(tolerance),
        maxIterations_(maxIterations),
        restart_(restart),
        warmStart_(warmStart),
        preconditioner_(preconditioner),
        history_(warmStart ? history : 0) {}
  static constexpr int kHistoryMinimumIterations = 3;
  const char* name() const override;
  LinearSolveResult solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) override;

 private:
  int minIterations() const { return history_.capacity() > 0 ? kHistoryMinimumIterations : 0; }
  LinearSolveResult solveFrom(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z);
  double tolerance_;
  int maxIterations_;
  int restart_;
  bool warmStart_;
  Preconditioner preconditioner_;
  // Automatic: the last step used the Hessian (the name() reports it); steps in a row started
  // with the Hessian.
  bool switched_ = false;
  int hessianRun_ = 0;
  bool factorValid_ = false;  // the system holds a clamped-Hessian factor of an earlier step
  int lastIterations_ = 0;    // of the last solve with that factor
  int factorizations_ = 0;    // Hessian factors made, and steps solved with one, in this pass
  int hessianSteps_ = 0;
  // The current run of Hessian steps: its cost in iterations with P (factorisations by
  // hessianFactorCost, iterations by hessianIterationCost) and its steps.
  double runCost_ = 0.0;
  int runSteps_ = 0;
  int stepHessianIterations_ = 0;  // of the current solve's iterations, with the Hessian
  Gmres gmres_;
  SolutionHistory history_;
};

}  // namespace weft
