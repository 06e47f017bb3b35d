#include <weft/diff/AdjointGrowth.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace weft {

void AdjointGrowth::observe(const NodeMatrix& z) {
  const double norm = z.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return;
  if (first_ == 0.0) first_ = norm;
  largest_ = std::max(largest_, norm);
}

double adjointGradientErrorEstimate(double growth, double tolerance) {
  return tolerance * std::sqrt(std::max(growth, 1.0)) / 100.0;
}

std::string adjointGrowthWarning(const AdjointSolverStats& stats, const std::string& method,
                                 double tolerance) {
  const double estimate = adjointGradientErrorEstimate(stats.adjointGrowth, tolerance);
  if (method == "direct" || !(estimate >= kAdjointGradientErrorWarning)) return "";
  char text[640];
  std::snprintf(text, sizeof text,
                "backward: the adjoint grew %.2g-fold over the pass (unstable modes of the "
                "linearised step, as in compressed cloth without bending) and each iterative "
                "solve's error (relative residual %.2g) grows with it: the gradient may be off by "
                "about %.1g (an order of magnitude, diff/AdjointGrowth.h); check it with "
                "solver.backward.method \"direct\" or a smaller solver.backward.tolerance",
                stats.adjointGrowth, tolerance, estimate);
  return text;
}

}  // namespace weft
