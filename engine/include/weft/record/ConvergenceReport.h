#pragma once
// How well a run's steps were solved: the steps that stopped at the iteration limit above the
// solver's tolerance, the worst residual, and the deepest node inside an obstacle's contact
// skin. Every command that runs the simulator reports it, so a capped solve is never passed off
// as a result.

#include <weft/record/StepStats.h>
#include <weft/scene/Scene.h>

#include <string>

namespace weft {

struct ConvergenceReport {
  int steps = 0;
  int unconverged = 0;         // steps that stopped at solver.pd_iterations above pd_tolerance
  double worstResidual = 0.0;  // m/s^2
  int worstResidualStep = 0;
  double maxDepth = 0.0;  // m, the deepest node inside an obstacle's skin (StepStats::depth)
  int maxDepthStep = 0;
  int unresolvedImpactSteps = 0;  // steps whose impact zones stopped at their round limit
  int firstUnresolvedImpactStep = 0;

  void add(const StepStats& s);
  // Depth beyond which a node counts as inside an obstacle in the warning (m).
  static constexpr double kDepthTolerance = 1e-4;
  // The lines to print on stderr ("warning: ..."), empty when every step converged and no node
  // ended deeper than kDepthTolerance inside an obstacle's skin.
  std::string warning(const SolverSettings& solver) const;
};

// The warning of a command that differentiates forward runs (gradcheck, optimize) when
// `unconvergedSteps` of their steps stopped at the iteration limit; empty when none did.
std::string unconvergedGradientWarning(int unconvergedSteps);

}  // namespace weft
