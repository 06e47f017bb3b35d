#include <weft/physics/ProjectiveDynamicsSolve.h>

#include <cmath>
#include <limits>

namespace weft {

ProjectiveDynamicsSolve::ProjectiveDynamicsSolve(const StepContext& ctx) {
  if (ctx.settings.acceleration == Acceleration::Anderson)
    anderson_.reset(3 * ctx.model.nodeCount(), ctx.settings.andersonWindow);
}

void ProjectiveDynamicsSolve::solve(StepContext& ctx) {
  const SolverSettings& solver = ctx.settings;
  if (solver.acceleration == Acceleration::Anderson)
    ctx.timed(ctx.solverModule, [&] { anderson_.restart(); });
  double previousEnergy = std::numeric_limits<double>::infinity();
  bool accelerated = false;
  while (ctx.stats.pdIterations < solver.pdIterations) {
    double energy = ctx.localStep(ctx.iterate);
    // Safeguard (Peng et al. 2018): an accelerated iterate that raised the energy is replaced by
    // the plain PD iterate, which never does (it minimises the surrogate of Eq. 6). The slack
    // absorbs round-off once the energy has converged to its last digits.
    if (accelerated && !(energy <= previousEnergy + 1e-13 * std::abs(previousEnergy))) {
      ctx.iterate = ctx.global;
      anderson_.restart();
      energy = ctx.localStep(ctx.iterate);
    }
    previousEnergy = energy;
    ctx.globalStep();
    if (ctx.checkConvergence()) return;
    ctx.timed(ctx.solverModule, [&] {
      if (solver.acceleration == Acceleration::Anderson) {
        anderson_.next(ctx.iterate.data(), ctx.global.data(), ctx.accelerated.data());
        ctx.iterate.swap(ctx.accelerated);
        accelerated = true;
      } else {
        ctx.iterate = ctx.global;
      }
    });
  }
}

}  // namespace weft
