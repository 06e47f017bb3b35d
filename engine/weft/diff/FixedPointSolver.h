#pragma once
// DiffCloth's local-global adjoint iteration (Eq. 20; Eq. 30 once contact adds Delta R):
//
//   P z_{k+1} = Delta P z_k + g,   z_0 = 0,
//
// one back-substitution with the prefactorised P per iteration. It converges when the spectral
// radius rho(P^{-1} Delta P) < 1 (Sec. 4.2, "Convergence"); on stiff, compressed cloth it does
// not, which is detected here (residual growth or the iteration cap) so that AdjointSolver can
// fall back. The residual of z_{k+1} is Delta P (z_{k+1} - z_k), which costs nothing extra: the
// next iteration needs Delta P z_{k+1} anyway.

#include <weft/diff/AdjointLinearSolver.h>

#include <vector>

namespace weft {

class FixedPointSolver final : public AdjointLinearSolver {
 public:
  // Stops when |g - K z| / |g| < tolerance; declares divergence when that ratio exceeds
  // divergenceRatio, is not finite, or keeps growing (see solve).
  FixedPointSolver(double tolerance, int maxIterations, double divergenceRatio = 1e3)
      : tolerance_(tolerance), maxIterations_(maxIterations), divergenceRatio_(divergenceRatio) {}
  const char* name() const override { return "fixed_point"; }
  LinearSolveResult solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) override;

 private:
  double tolerance_;
  int maxIterations_;
  double divergenceRatio_;
  NodeMatrix deltaPz_, nextDeltaPz_;
  std::vector<double> history_;  // residual per iteration
  static constexpr std::size_t kWindow = 10;
};

}  // namespace weft
