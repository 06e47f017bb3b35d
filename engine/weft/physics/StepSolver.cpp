#include <weft/physics/StepSolver.h>

#include <weft/physics/ActiveSetSolve.h>
#include <weft/physics/ContactNewtonSolve.h>
#include <weft/physics/NewtonPcgSolve.h>
#include <weft/physics/PdContactSolve.h>
#include <weft/physics/ProjectiveDynamicsSolve.h>

namespace weft {

std::unique_ptr<StepSolver> makeStepSolver(StepContext& ctx) {
  if (ctx.contact) {
    switch (ctx.settings.contact) {
      case ContactMethod::ActiveSet:
        return std::make_unique<ActiveSetSolve>();
      case ContactMethod::Newton:
        return std::make_unique<ContactNewtonSolve>(ctx);
      case ContactMethod::ProjectiveDynamics:
        break;
    }
    return std::make_unique<PdContactSolve>(ctx);
  }
  if (ctx.settings.method == SolverMethod::Newton) return std::make_unique<NewtonPcgSolve>();
  return std::make_unique<ProjectiveDynamicsSolve>(ctx);
}

}  // namespace weft
