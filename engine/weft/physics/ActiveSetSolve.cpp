#include <weft/physics/ActiveSetSolve.h>

#include <weft/contact/FrictionalContact.h>
#include <weft/physics/NewtonPcgSolve.h>

namespace weft {

void ActiveSetSolve::prepareContacts(StepContext& ctx) {
  ctx.contact->prepareActiveSet(ctx.start, ctx.settings.pdTolerance * ctx.h);
}

void ActiveSetSolve::solve(StepContext& ctx) {
  ActiveContactSet& set = ctx.contact->activeSet();
  if (set.empty()) {
    NewtonPcgSolve::iterate(ctx, nullptr);
    return;
  }
  // Active-set Newton (ActiveContactSet.h). Convergence test of the contact solve: no branch
  // change and no friction impulse change above pd_tolerance * h as a velocity (m/s), the
  // velocity error the elastic tolerance allows over one step, together with the elastic
  // residual below pd_tolerance.
  ctx.timed(ctx.contactSolveModule, [&] {
    set.guessBranches(ctx.iterate);
    set.projectPositions(ctx.iterate);
  });
  NewtonPcgSolve::iterate(ctx, &set);
  ctx.timed(ctx.contactSolveModule, [&] { set.refreshVelocities(ctx.iterate); });
  ctx.stats.contactSweepChange = set.lastChange();
  // The feasible iterate is the step's result (a PD solve past it would leave the constraints).
  ctx.global = ctx.iterate;
}

void ActiveSetSolve::record(const StepContext& ctx, StepContacts& out) const {
  ctx.contact->activeSet().record(out);
}

}  // namespace weft
