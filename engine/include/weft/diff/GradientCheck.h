#pragma once
// Adjoint gradient vs central finite differences of the task loss, per parameter (what
// `weft gradcheck` prints). Both use the same tightened forward solver (withTightForwardSolver),
// so their difference measures the adjoint, not the forward solver's stopping noise; the adjoint
// solves are tightened too (backwardTolerance replaces solver.backward.tolerance, which is the
// setting for optimisation) and checked against solver.backward.accuracy like any gradient
// (GradientErrorControl.h). The relative error of the gradient follows the backward tolerance,
// while the forward tolerance mostly shows up as noise in the finite differences, down to the
// forward residual's round-off floor (docs/how-it-works/backward.md).
//
// Finite differences: L'(theta) ~ (L(theta + d) - L(theta - d)) / (2 d) with the relative step
// d = eps * |theta| (d = eps when theta = 0). Relative error: |adjoint - fd| / max(|adjoint|,
// |fd|) (0 when both are 0).

#include <weft/diff/AdjointSolver.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ParameterSet.h>

#include <optional>
#include <string>
#include <vector>

namespace weft {

struct GradientCheckOptions {
  double eps = 1e-4;                // relative finite-difference step
  double forwardTolerance = 1e-8;   // pd_tolerance (m/s^2) of every forward run, Newton-PCG
  double backwardTolerance = 1e-8;  // relative residual of every adjoint solve
  std::optional<std::string> backwardMethod;  // overrides solver.backward.method
};

struct GradientCheckEntry {
  std::string param;
  double value = 0.0, step = 0.0;
  double adjoint = 0.0, finiteDifference = 0.0, relativeError = 0.0;
  double errorEstimate = 0.0;  // the adjoint's estimated absolute error (GradientErrorControl.h)
};

struct GradientCheckReport {
  double loss = 0.0;
  std::vector<GradientCheckEntry> entries;
  AdjointSolverStats backward;
  GradientErrorEstimate error;  // the adjoint's
  std::string backwardMethod;
  double backwardTolerance = 0.0;
  int forwardRuns = 0;
  int unconvergedSteps = 0;  // over all forward runs
  double seconds = 0.0;
  double maxRelativeError() const;
};

double relativeError(double a, double b);

// The check's adjoint half on its own: the task loss's gradient by the adjoint pass, with the
// forward run and the adjoint solves tightened as above (eps is not used). checkGradient reports
// these values as its adjoint; the Python module's weft.gradient returns them.
struct TightAdjointGradient {
  Scene scene;                // the scene with the tightened forward solver
  BackwardSettings backward;  // the tightened adjoint solves' settings
  GradientResult result;      // loss, dL/dtheta in the ParameterSet's order, solver statistics
  int unconvergedSteps = 0;   // of the forward run
};
TightAdjointGradient tightAdjointGradient(const Scene& scene, const ParameterSet& parameters,
                                          const GradientCheckOptions& options);

GradientCheckReport checkGradient(const Scene& scene, const ParameterSet& parameters,
                                  const GradientCheckOptions& options);

}  // namespace weft
