#pragma once
// One time step's solve, as a strategy the Simulator delegates to (one class per solver, one
// file each). The Simulator builds the modules, starts the step (forces, y, the warm-started
// iterate in StepContext), detects contacts, calls prepareContacts and solve, adds contacts the
// solved path met (resolvesMissedContacts), records them (record), checks for non-finite values
// and advances the state to StepContext::global.
//
// Without contact (solver.method): NewtonPcgSolve ("newton", the default) or
// ProjectiveDynamicsSolve ("pd", Anderson-accelerated unless solver.acceleration is "none").
// With contact (solver.contact): ContactNewtonSolve ("newton", the default), PdContactSolve
// ("pd") or ActiveSetSolve ("active_set"). See each class for its method.

#include <weft/physics/StepContext.h>
#include <weft/record/StepContacts.h>

#include <memory>

namespace weft {

class StepSolver {
 public:
  virtual ~StepSolver() = default;

  // Contact scenes, after detection: hands the step's contacts to the contact solve.
  virtual void prepareContacts(StepContext& /*ctx*/) {}
  // Solves the step from ctx.iterate until ctx.stats.pdIterations reaches ctx.solveLimit (or
  // the solver's own budget) or the residual is below solver.pd_tolerance; leaves the step's
  // result in ctx.global and fills ctx.stats (iterations, residual, convergence, contact
  // sweeps).
  virtual void solve(StepContext& ctx) = 0;
  // Whether the step is solved again with the contacts the solved path violated and detection
  // missed (FrictionalContact::addMissedContacts), after prepareContacts.
  virtual bool resolvesMissedContacts() const { return false; }
  // Contact scenes: the step's contacts as the last solve left them.
  virtual void record(const StepContext& /*ctx*/, StepContacts& /*out*/) const {}
};

// The solver the scene's solver.contact (contact scenes: ctx.contact set) or solver.method asks
// for.
std::unique_ptr<StepSolver> makeStepSolver(StepContext& ctx);

}  // namespace weft
