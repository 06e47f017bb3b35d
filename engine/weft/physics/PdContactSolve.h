#pragma once
// solver.contact = "pd" (the paper's method): DiffCloth's velocity-form PD with the
// per-node Signorini-Coulomb solve inside every global step (Sec. 3.2, Eqs. 10-12, notes
// Sec. 2.1; ContactSolver.h). solver.acceleration applies: "anderson" (default) mixes the
// iterates with a residual-based safeguard, "none" runs plain PD. It stops on the same residual
// as without contact, which then includes the contact impulse; on stiff cloth it often reaches
// the iteration cap first. Steps without contacts are Newton-PCG when solver.method is
// "newton".
//
// Its global step and residual are also those of the semismooth Newton contact solve
// (ContactNewtonSolve), which finishes a stalled step with this iteration.

#include <weft/physics/AndersonAccelerator.h>
#include <weft/physics/StepSolver.h>

namespace weft {

class PdContactSolve final : public StepSolver {
 public:
  explicit PdContactSolve(const StepContext& ctx);
  // The detected contacts to the per-node solver, the law solved with the lumped mass.
  void prepareContacts(StepContext& ctx) override;
  void solve(StepContext& ctx) override;
  bool resolvesMissedContacts() const override { return true; }
  void record(const StepContext& ctx, StepContacts& out) const override;

  // The PD contact iteration from ctx.iterate until ctx.stats.pdIterations reaches
  // ctx.solveLimit or the residual is below tolerance; the per-node solver must have been
  // prepared with the lumped mass.
  void iterate(StepContext& ctx);
  // ctx.rhs = b(x) + h r(f(x)) with the contact solve at x (the law solved with `lawMass`), and
  // P x into systemTimesX.
  static void assembleRhs(StepContext& ctx, const NodeMatrix& x, NodeMatrix& systemTimesX,
                          const Eigen::VectorXd& lawMass);
  // G(x) = P x - b(x) - h r(f(x)) into `residual` (ctx.rhs = b(x) + h r); returns its
  // mass-weighted RMS (StepContext::residualOf).
  static double residual(StepContext& ctx, const NodeMatrix& x, NodeMatrix& residual,
                         const Eigen::VectorXd& lawMass);

 private:
  // Velocity-form global step with contact: ctx.global = P^-1 (b + h r) at ctx.iterate.
  void globalStep(StepContext& ctx);

  AndersonAccelerator anderson_;
};

}  // namespace weft
