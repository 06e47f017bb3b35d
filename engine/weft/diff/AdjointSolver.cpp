#include <weft/diff/AdjointSolver.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/DirectLuSolver.h>
#include <weft/diff/FixedPointSolver.h>
#include <weft/diff/GmresSolver.h>

#include <chrono>
#include <cstdio>

namespace weft {

std::unique_ptr<AdjointLinearSolver> makeAdjointLinearSolver(const BackwardSettings& settings) {
  if (settings.method == "fixed_point")
    return std::make_unique<FixedPointSolver>(settings.tolerance, settings.maxIterations);
  if (settings.method == "direct") return std::make_unique<DirectLuSolver>();
  return std::make_unique<GmresSolver>(settings.tolerance, settings.maxIterations);
}

AdjointSolver::AdjointSolver(const BackwardSettings& settings)
    : settings_(settings), primary_(makeAdjointLinearSolver(settings)) {}

AdjointSolver::~AdjointSolver() = default;

void AdjointSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z, int step) {
  const auto start = std::chrono::steady_clock::now();
  LinearSolveResult r = primary_->solve(system, rhs, z);
  ++stats_.solves;
  stats_.iterations += r.iterations;
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
      stats_.fallbackSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - fallbackStart).count();
    } else {
      char what[160];
      std::snprintf(what, sizeof what,
                    "adjoint solve (%s) did not converge: relative residual %.3g after %d iterations "
                    "(solver.backward.fallback is \"none\")",
                    primary_->name(), r.residual, r.iterations);
      throw NumericalError(step, "backward", what);
    }
  }
  if (!r.converged) {
    char what[120];
    std::snprintf(what, sizeof what, "direct sparse LU of K = P - Delta P failed (singular matrix, residual %.3g)",
                  r.residual);
    throw NumericalError(step, "backward", what);
  }
  stats_.maxResidual = std::max(stats_.maxResidual, r.residual);
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace weft
