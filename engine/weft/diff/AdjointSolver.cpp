#include <weft/diff/AdjointSolver.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/DirectLuSolver.h>
#include <weft/diff/FixedPointSolver.h>
#include <weft/diff/GmresSolver.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace weft {

std::unique_ptr<AdjointLinearSolver> makeAdjointLinearSolver(const BackwardSettings& settings) {
  if (settings.method == "fixed_point")
    return std::make_unique<FixedPointSolver>(settings.tolerance, settings.maxIterations);
  if (settings.method == "direct") return std::make_unique<DirectLuSolver>();
  // No restart below 200 iterations: on stretched cloth GMRES preconditioned by P needs up to
  // about 200 iterations per step at 1e-6, and restarting earlier loses the Krylov space it needs
  // (docs/benchmarks.md, "GMRES without restarts"). The basis costs 2 x 200 x 3m doubles.
  // Each step starts from the previous step's z, or from the best combination of the last
  // settings.history solutions (SolutionHistory).
  return std::make_unique<GmresSolver>(
      settings.tolerance, settings.maxIterations, std::min(settings.maxIterations, 200),
      /*warmStart=*/true,
      settings.preconditioner == "hessian" ? GmresSolver::Preconditioner::ClampedHessian
      : settings.preconditioner == "p"     ? GmresSolver::Preconditioner::P
                                           : GmresSolver::Preconditioner::Automatic,
      settings.history);
}

void addSolverCosts(AdjointSolverStats& into, const AdjointSolverStats& from) {
  into.solves += from.solves;
  into.iterations += from.iterations;
  into.maxIterations = std::max(into.maxIterations, from.maxIterations);
  into.hessianIterations += from.hessianIterations;
  into.hessianFactorizations += from.hessianFactorizations;
  into.notConverged += from.notConverged;
  into.diverged += from.diverged;
  into.fallbacks += from.fallbacks;
  into.maxResidual = std::max(into.maxResidual, from.maxResidual);
  into.seconds += from.seconds;
  into.fallbackSeconds += from.fallbackSeconds;
  into.adjointGrowth = std::max(into.adjointGrowth, from.adjointGrowth);
}

AdjointSolver::AdjointSolver(const BackwardSettings& settings)
    : settings_(settings), primary_(makeAdjointLinearSolver(settings)) {}

AdjointSolver::~AdjointSolver() = default;

void AdjointSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z, int step) {
  const auto start = std::chrono::steady_clock::now();
  LinearSolveResult r = primary_->solve(system, rhs, z);
  ++stats_.solves;
  stats_.iterations += r.iterations;
  stats_.hessianIterations += r.hessianIterations;
  stats_.hessianFactorizations += r.factorizations;
  stats_.maxIterations = std::max(stats_.maxIterations, r.iterations);
  const bool iterative = settings_.method != "direct";
  if (!r.converged && iterative) {
    ++stats_.notConverged;
    if (r.diverged) ++stats_.diverged;
    if (settings_.fallback == "direct") {
      if (!direct_) direct_ = std::make_unique<DirectLuSolver>();
      ++stats_.fallbacks;
      const auto fallbackStart = std::chrono::steady_clock::now();
      r = direct_->solve(system, rhs, z);
      stats_.fallbackSeconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - fallbackStart).count();
    } else {
      char what[160];
      std::snprintf(
          what, sizeof what,
          "adjoint solve (%s) did not converge: relative residual %.3g after %d iterations "
          "(solver.backward.fallback is \"none\")",
          primary_->name(), r.residual, r.iterations);
      throw NumericalError(step, "backward", what);
    }
  }
  if (!r.converged) {
    char what[120];
    std::snprintf(what, sizeof what,
                  "direct sparse LU of K = P - Delta P failed (singular matrix, residual %.3g)",
                  r.residual);
    throw NumericalError(step, "backward", what);
  }
  stats_.maxResidual = std::max(stats_.maxResidual, r.residual);
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace weft
