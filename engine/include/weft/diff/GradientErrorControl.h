#pragma once
// A parameter gradient that meets a requested relative accuracy (solver.backward.accuracy),
// returned with its error estimate. An iterative backward pass's error comes from its per-step
// solves: each is accurate to its relative residual, and the recursion carries that error to the
// earlier steps, amplified as the adjoint grows (AdjointGrowth.h): on a buckling cloth by 1e5 to
// 1e11, where the default residual 1e-4 leaves a gradient off by orders of magnitude. Nothing
// cheap bounds that beforehand, so it is measured: a pass at tolerance t and one at t / 100 on
// the same trajectory, whose difference is the estimate for the tighter one (an upper estimate,
// as the error falls with the tolerance; never below the tight pass's own size, which the
// difference cannot see where both passes accept the same solutions). While it exceeds the
// accuracy, the pair moves down by 100 to kTightestTolerance, and then the direct sparse LU is the
// reference. A direct pass is made once: its error is round-off. The forward pass is taken as
// given.

#include <weft/diff/Backpropagation.h>

#include <string>

namespace weft {

// The tightest iterative tolerance the ladder tries before the direct solve.
constexpr double kTightestTolerance = 1e-12;
// The factor between the two passes of a pair, and between one pair and the next.
constexpr double kToleranceStep = 100.0;

// The estimate of one pass on its own (backpropagate fills it): the fit tolerance *
// sqrt(growth) / 100 for an iterative pass, epsilon * growth for a direct one.
GradientErrorEstimate singlePassErrorEstimate(const GradientResult& result,
                                              const BackwardSettings& settings);

// Backward passes with error control, remembering across calls (an optimiser's evaluations) the
// pair that last met the accuracy, so that a run pays two passes per gradient once it has found
// it. Not thread-safe; one per objective.
class AccurateBackward {
 public:
  explicit AccurateBackward(const BackwardSettings& settings);
  // The gradient of `loss` over `trajectory`: with settings.accuracy 0 or the direct method,
  // one pass; otherwise the tighter pass of the first pair that agrees to settings.accuracy (or
  // the last tried, with error.met false). `seconds` and the solver's costs cover every pass;
  // its largest residual and growth are the returned pass's.
  // `progress` (optional) hears of every step of every pass.
  GradientResult differentiate(const Trajectory& trajectory, const TaskLoss& loss,
                               const ParameterSet& parameters, const StepProgress& progress = {});
  // The looser tolerance of the pair the next call starts from.
  double startTolerance() const { return start_; }

 private:
  BackwardSettings settings_;
  double start_;
};

// One-off: AccurateBackward(settings).differentiate(...).
GradientResult backpropagateToAccuracy(const Trajectory& trajectory, const TaskLoss& loss,
                                       const ParameterSet& parameters,
                                       const BackwardSettings& settings);

// One line for a command's summary: "gradient error 3.1e-05 (against tolerance 1e-06; 2 passes;
// accuracy 0.001 met)".
std::string describeGradientError(const GradientErrorEstimate& error);

// What a command prints (after "warning: ") for a gradient whose estimated error misses the
// requested accuracy, or, uncontrolled, reaches kAdjointGradientErrorWarning; "" otherwise.
std::string gradientErrorWarning(const GradientErrorEstimate& error);

}  // namespace weft
