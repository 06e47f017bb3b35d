#pragma once
// A solver of one backward step's linear system K z = g (AdjointSystem). Three implementations
// share this interface: FixedPointSolver (DiffCloth Eq. 20/30), GmresSolver (Krylov,
// preconditioned by P's factor) and DirectLuSolver (UMFPACK sparse LU). AdjointSolver picks one
// from the scene's solver.backward settings and falls back to the direct one.

#include <weft/core/Types.h>

namespace weft {

class AdjointSystem;

struct LinearSolveResult {
  bool converged = false;
  bool diverged = false;  // stopped early because the iteration was growing (fixed point)
  int iterations = 0;     // preconditioner applications (iterative solvers); 0 for the direct one
  double residual = 0.0;  // |g - K z|_2 / |g|_2 at the returned z
  int hessianIterations = 0;  // of `iterations`, with the clamped Hessian's factor (GmresSolver)
  int factorizations = 0;     // clamped-Hessian factorisations made for this solve (GmresSolver)
};

class AdjointLinearSolver {
 public:
  virtual ~AdjointLinearSolver() = default;
  virtual const char* name() const = 0;
  // Solves K z = rhs for the system's prepared state; z is overwritten.
  virtual LinearSolveResult solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) = 0;
};

// |a|_2 of an m x 3 block taken as one 3m vector, and the matching dot product.
inline double blockDot(const NodeMatrix& a, const NodeMatrix& b) {
  return (a.array() * b.array()).sum();
}

}  // namespace weft
