#include <weft/record/ConvergenceReport.h>

#include <cstdio>

namespace weft {

void ConvergenceReport::add(const StepStats& s) {
  ++steps;
  if (!s.converged) {
    ++unconverged;
    if (s.residual > worstResidual) worstResidual = s.residual, worstResidualStep = s.step;
  }
  if (s.depth > maxDepth) maxDepth = s.depth, maxDepthStep = s.step;
  if (!s.impactsResolved && unresolvedImpactSteps++ == 0) firstUnresolvedImpactStep = s.step;
}

std::string ConvergenceReport::warning(const SolverSettings& solver) const {
  std::string text;
  char line[512];
  if (unconverged > 0) {
    std::snprintf(
        line, sizeof line,
        "warning: %d of %d steps stopped at the iteration limit (solver.pd_iterations "
        "%d) above solver.pd_tolerance %.3g m/s^2; worst residual %.3g m/s^2 at step %d\n",
        unconverged, steps, solver.pdIterations, solver.pdTolerance, worstResidual,
        worstResidualStep);
    text += line;
  }
  if (maxDepth > kDepthTolerance) {
    std::snprintf(line, sizeof line,
                  "warning: a node ended %.3g mm inside an obstacle's contact skin at step %d\n",
                  1e3 * maxDepth, maxDepthStep);
    text += line;
  }
  if (unresolvedImpactSteps > 0) {
    std::snprintf(line, sizeof line,
                  "warning: impact zones left impacts unresolved in %d of %d steps (first at step "
                  "%d): those steps are not collision-free\n",
                  unresolvedImpactSteps, steps, firstUnresolvedImpactStep);
    text += line;
  }
  return text;
}

std::string unconvergedGradientWarning(int unconvergedSteps) {
  if (unconvergedSteps <= 0) return "";
  return "warning: " + std::to_string(unconvergedSteps) +
         " forward steps stopped at solver.pd_iterations above solver.pd_tolerance: the "
         "gradient is that of unconverged steps, and finite differences there measure the "
         "iteration limit, not the physics\n";
}

}  // namespace weft
