#pragma once
// The per-step adjoint solve with the method the scene asks for (solver.backward.method:
// "gmres", default, "fixed_point" or "direct"), its tolerance and iteration cap
// (solver.backward.tolerance, .max_iterations), and the fallback of DiffCloth Sec. 4.2: when the
// iterative method does not converge, the step is solved again by the direct sparse LU
// (solver.backward.fallback = "direct", default), or the backward pass fails with a
// NumericalError ("none"). Counts iterations, non-converged solves and fallbacks.

#include <weft/diff/AdjointLinearSolver.h>
#include <weft/scene/Scene.h>

#include <memory>
#include <string>

namespace weft {

class AdjointSystem;

struct AdjointSolverStats {
  int solves = 0;
  long long iterations = 0;         // solves with P's factor by the chosen iterative method
  int maxIterations = 0;            // the most any single step needed
  long long hessianIterations = 0;  // of `iterations`, preconditioned by the clamped Hessian
  int hessianFactorizations = 0;    // clamped-Hessian factorisations (GmresSolver "hessian"/"auto")
  int notConverged = 0;      // steps where the chosen method failed (diverged or hit the cap)
  int diverged = 0;          // of those, stopped early on residual growth
  int fallbacks = 0;         // steps solved again by the direct LU
  double maxResidual = 0.0;  // largest relative residual accepted
  double seconds = 0.0;
  double fallbackSeconds = 0.0;  // of `seconds`, spent in the direct fallback after a failed solve
  // Set by the backward pass (AdjointGrowth.h): max |z_n| over the first nonzero |z_n|; over
  // several passes, the largest.
  double adjointGrowth = 1.0;
};

// Adds what `from` cost (solves, iterations, factorisations, failures, seconds) to `into`; the
// largest residual and growth are the larger of the two.
void addSolverCosts(AdjointSolverStats& into, const AdjointSolverStats& from);

class AdjointSolver {
 public:
  explicit AdjointSolver(const BackwardSettings& settings);
  ~AdjointSolver();
  const std::string& method() const { return settings_.method; }

  // Solves K z = rhs for the system's prepared state (`step` names the failure, 1-based).
  // Throws NumericalError when no solver (including the fallback) gives a finite solution
  // within tolerance.
  void solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z, int step);
  const AdjointSolverStats& stats() const { return stats_; }

 private:
  BackwardSettings settings_;
  std::unique_ptr<AdjointLinearSolver> primary_;
  std::unique_ptr<AdjointLinearSolver> direct_;
  AdjointSolverStats stats_;
};

// Makes one of the three solvers by name ("gmres", "fixed_point", "direct").
std::unique_ptr<AdjointLinearSolver> makeAdjointLinearSolver(const BackwardSettings& settings);

}  // namespace weft
