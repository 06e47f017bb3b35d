#include <weft/physics/PdContactSolve.h>

#include <weft/contact/FrictionalContact.h>
#include <weft/physics/NewtonPcgSolve.h>

#include <cmath>
#include <limits>

namespace weft {

PdContactSolve::PdContactSolve(const StepContext& ctx) {
  if (ctx.settings.acceleration == Acceleration::Anderson)
    anderson_.reset(3 * ctx.model.nodeCount(), ctx.settings.andersonWindow);
}

void PdContactSolve::prepareContacts(StepContext& ctx) {
  ctx.contact->prepareSolve(nullptr);
}

void PdContactSolve::solve(StepContext& ctx) {
  // A step whose contact set is empty has an energy, g (Eq. 3): with solver.method "newton" it
  // is solved as in a scene without obstacles, Newton with an Armijo line search on g and the
  // PD step as the fallback, which always decreases g. Neither contact solve has that
  // globalisation: the semismooth one backtracks on the residual norm, which a direction of the
  // indefinite K of compressed, buckling cloth need not decrease (the Sock's tube hanging from
  // its cuff: steps starting at a residual of 8.6e2 m/s^2 stalled at 3 to 30 with either
  // contact solve; this way every such step converges, in about 80 solves with P).
  if (ctx.contact->perNodeSolver().empty() && ctx.settings.method == SolverMethod::Newton) {
    NewtonPcgSolve::iterate(ctx, nullptr);
    return;
  }
  iterate(ctx);
}

void PdContactSolve::iterate(StepContext& ctx) {
  // PD iterations with the contact solve in each global step (Ly et al. 2020, DiffCloth Eq. 12).
  // Convergence test: the same mass-weighted RMS imbalance as without contact,
  // |P (x^{k+1} - x^k)| / h^2 = |b(x^k) + h r(x^k) - P x^k| / h^2: the residual of the
  // implicit-Euler equations with the contact force at the iterate. It vanishes only when the
  // iterate and the contact impulses both stop changing, i.e. at a solution of Eq. 9.
  //
  // Anderson acceleration (solver.acceleration = "anderson") mixes the last iterates of the
  // fixed-point map x -> G(x) (one such global step). The energy safeguard of the no-contact
  // solver does not apply (friction dissipates, the law is non-smooth), so the safeguard is on
  // the residual: an accelerated iterate whose residual exceeds the previous iterate's is
  // replaced by the plain image of that previous iterate, and the history restarts.
  const SolverSettings& solver = ctx.settings;
  const bool anderson = solver.acceleration == Acceleration::Anderson;
  if (anderson) anderson_.restart();
  double previousResidual = std::numeric_limits<double>::infinity();
  bool accelerated = false;
  while (ctx.stats.pdIterations < ctx.solveLimit) {
    ctx.localStep(ctx.iterate);
    globalStep(ctx);
    if (ctx.checkConvergence()) return;
    if (!anderson) {
      ctx.timed(ctx.solverModule, [&] { ctx.iterate = ctx.global; });
      continue;
    }
    if (accelerated && !(ctx.stats.residual <= previousResidual)) {
      ctx.timed(ctx.solverModule, [&] {
        ctx.iterate = ctx.plainIterate;
        anderson_.restart();
      });
      accelerated = false;
      continue;
    }
    previousResidual = ctx.stats.residual;
    ctx.timed(ctx.solverModule, [&] {
      ctx.plainIterate = ctx.global;
      anderson_.next(ctx.iterate.data(), ctx.global.data(), ctx.accelerated.data());
      ctx.iterate.swap(ctx.accelerated);
    });
    accelerated = true;
  }
}

void PdContactSolve::globalStep(StepContext& ctx) {
  // Velocity-form global step with contact (DiffCloth Eqs. 10-12): x = P^-1 (b + h r).
  assembleRhs(ctx, ctx.iterate, ctx.fullResidual,
              ctx.model.mass);  // (P x in fullResidual, scratch)
  ctx.timed(ctx.solverModule, [&] {
    ctx.global = ctx.rhs;
    ctx.system.solveInPlace(ctx.global);
    ctx.change = ctx.global - ctx.iterate;
  });
  ++ctx.stats.pdIterations;
}

void PdContactSolve::assembleRhs(StepContext& ctx, const NodeMatrix& x, NodeMatrix& systemTimesX,
                                 const Eigen::VectorXd& lawMass) {
  // rhs = b(x) + h r(f(x)) (DiffCloth Eqs. 10-12; notes Sec. 2.1) from the last local step's
  // projections, and P x. In positions, P v = b_hat + r is P x = b + h r.
  ctx.timed(ctx.solverModule, [&] {
    ctx.rhs = ctx.massY;
    for (std::size_t c = 0; c < ctx.constraints.size(); ++c)
      if (!ctx.constraints[c]->projectsToZero())
        ctx.constraints[c]->gather(ctx.projections[c], ctx.h * ctx.h, ctx.rhs);
    ctx.system.multiply(x, systemTimesX);
  });
  if (ctx.contact->empty()) return;
  ctx.timed(ctx.solverModule, [&] {
    // Free momentum f = b_hat - (P - M) v^k = M (x^k - x_n)/h + (b - P x^k)/h, which equals
    // M v_n + h (f_ext + f_int(x^k)): the momentum each node would have without contact,
    // predicted with the diagonal M as in Eq. 12. The Newton solve uses its law mass m~ in place
    // of M (ContactSolver::setContacts): the same solution, other iterates.
    ctx.freeMomentum = (ctx.rhs - systemTimesX + lawMass.asDiagonal() * (x - ctx.start)) / ctx.h;
  });
  ctx.timed(ctx.contactSolveModule, [&] {
    // Sweeps stop when no impulse changes by more than a tenth of what the PD tolerance allows
    // over one step (as a velocity); see ContactSolver.h.
    ctx.stats.contactSweeps +=
        ctx.contact->solve(ctx.freeMomentum, 0.1 * ctx.settings.pdTolerance * ctx.h);
    ctx.stats.contactSweepChange = ctx.contact->lastSweepChange();
    ctx.contact->addImpulses(ctx.h, ctx.rhs);
  });
}

double PdContactSolve::residual(StepContext& ctx, const NodeMatrix& x, NodeMatrix& residual,
                                const Eigen::VectorXd& lawMass) {
  ctx.localStep(x, false);  // (the Newton solve's test is the residual, not the energy)
  assembleRhs(ctx, x, residual, lawMass);
  double measure = 0.0;
  ctx.timed(ctx.solverModule, [&] {
    residual -= ctx.rhs;
    measure = ctx.residualOf(residual);
  });
  return measure;
}

void PdContactSolve::record(const StepContext& ctx, StepContacts& out) const {
  ctx.contact->record(out);
}

}  // namespace weft
