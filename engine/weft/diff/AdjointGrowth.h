#pragma once
// How much the adjoint z_n grew over a backward pass, and when that makes an iterative solve's
// gradient untrustworthy. Each step's solve K z_n = g_n is accurate to its relative residual;
// the recursion then carries its error to the earlier steps (g_{n-1} holds M z_n, Eq. 16). Where
// the linearised step has unstable modes (a cloth without bending in compression buckles: K has
// small or negative eigenvalues), z grows exponentially in them and so does every step's error,
// while the gradient, a sum over steps, is mostly cancellation.
// Growth = max_n |z_n| / (the first nonzero |z_n| of the pass, in backward order).
//
// Measured 2026-12-02 (relative error of the GMRES gradient against the direct one, at relative
// residuals 1e-4 / 1e-6):
//   the DiffCloth authors' soft napkin (wind_reference.json, 200 steps, trajectory loss; `weft
//   bench backward --scenes wind_reference --resolutions 12,24,48`): growth 1.8e5, 1.25e8, 3.1e11
//   at 12^2, 24^2, 48^2; error 8.8e-5 / 9.0e-7, 2.1e-2 / 7.2e-6, 1.97 / 8.1e-3. At 48^2 the
//   direct gradient agrees with central differences to 1.1e-4 (docs/benchmarks.md);
//   sphere_sysid (`weft gradcheck --backward direct|gmres --backward-tolerance T`, forward at
//   1e-8): growth 1.2e9, error 1.8e-3 / 8.9e-5;
//   flag (the same commands): growth 890, error 8.0e-4 at 1e-4.

#include <weft/core/Types.h>
#include <weft/diff/AdjointSolver.h>

#include <string>

namespace weft {

// A rough size for the relative error of an iterative backward pass's gradient from its solves'
// relative residual `tolerance` and the pass's growth: tolerance * sqrt(growth) / 100. A fit to
// the measurements above, not a bound: for growth from 1e5 up it is within a factor of 20 of the
// measured error (4x under at 48^2 and 1e-4: 0.55 against 1.97; 19x over on sphere_sysid at
// 1e-4: 3.5e-2 against 1.8e-3); at small growth it is under the error (flag: 3e-5 against
// 8.0e-4), which is then small anyway.
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
