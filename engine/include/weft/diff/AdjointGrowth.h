#pragma once
// How much the adjoint z_n grew over a backward pass, and when that makes an iterative solve's
// gradient untrustworthy. Each step's solve K z_n = g_n is accurate to its relative residual;
// the recursion then carries its error to the earlier steps (g_{n-1} holds M z_n, Eq. 16). Where
// the linearised step has unstable modes (a cloth without bending in compression buckles: K has
// small or negative eigenvalues), z grows exponentially in them and so does every step's error,
// while the gradient, a sum over steps, is mostly cancellation.
// Growth = max_n |z_n| / (the first nonzero |z_n| of the pass, in backward order). Growth and
// gradient error measured on the soft napkin, sphere_sysid and the Flag:
// docs/how-it-works/backward.md, "When the tolerance is not enough".

#include <weft/core/Types.h>
#include <weft/diff/AdjointSolver.h>

#include <string>

namespace weft {

// A rough size for the relative error of an iterative backward pass's gradient from its solves'
// relative residual `tolerance` and the pass's growth: tolerance * sqrt(growth) / 100. A fit to
// measurements (docs/how-it-works/backward.md), not a bound: for growth from 1e5 up it is within
// a factor of 20 of the measured error; at small growth it is under the error, which is then
// small anyway.
double adjointGradientErrorEstimate(double growth, double tolerance);
// Commands warn when that estimate reaches this.
constexpr double kAdjointGradientErrorWarning = 1e-3;

class AdjointGrowth {
 public:
  void observe(const NodeMatrix& z);
  double factor() const { return first_ > 0.0 ? largest_ / first_ : 1.0; }

 private:
  double first_ = 0.0, largest_ = 0.0;
};

// The warning a command prints for a backward pass with these statistics, solved by `method` at
// `tolerance` (solver.backward), or "" (direct solves, or an estimate below
// kAdjointGradientErrorWarning).
std::string adjointGrowthWarning(const AdjointSolverStats& stats, const std::string& method,
                                 double tolerance);

}  // namespace weft
