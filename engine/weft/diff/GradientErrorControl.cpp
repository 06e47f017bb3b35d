#include <weft/diff/GradientErrorControl.h>

#include <weft/diff/AdjointGrowth.h>

#include <algorithm>
#include <cstdio>
#include <limits>

namespace weft {

namespace {

GradientResult pass(const Trajectory& trajectory, const TaskLoss& loss,
                    const ParameterSet& parameters, BackwardSettings settings, double tolerance,
                    const StepProgress& progress, int number) {
  if (tolerance > 0.0) {
    settings.tolerance = tolerance;
  } else {
    settings.method = "direct";
  }
  return backpropagate(trajectory, loss, parameters, settings, progress, number);
}

// The estimate for `tight` (solved at `tolerance`, 0: direct) from its difference to `loose`.
// The difference says nothing below the tight pass's own error: where both passes accept the
// same solutions (a warm start already within the tighter tolerance, as near an optimum where
// the loss's gradient is tiny) it is zero. So the estimate is at least that pass's own size, the
// fit for its tolerance and growth (or epsilon times the growth for the direct solve).
GradientErrorEstimate difference(const GradientResult& loose, const GradientResult& tight,
                                 double tolerance, double requested) {
  GradientErrorEstimate e;
  e.absolute = (loose.gradient - tight.gradient).cwiseAbs();
  const double norm = tight.gradient.norm();
  const double gap = e.absolute.norm();
  const double growth = std::max(tight.solver.adjointGrowth, 1.0);
  const double floor = tolerance > 0.0 ? adjointGradientErrorEstimate(growth, tolerance)
                                       : std::numeric_limits<double>::epsilon() * growth;
  e.relative = norm > 0.0 ? std::max(gap / norm, floor)
                          : (gap > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  e.absolute = e.absolute.cwiseMax(floor * norm);
  e.requested = requested;
  e.met = e.relative <= requested;
  e.basis = "difference";
  return e;
}

}  // namespace

AccurateBackward::AccurateBackward(const BackwardSettings& settings)
    : settings_(settings), start_(settings.tolerance) {}

GradientResult AccurateBackward::differentiate(const Trajectory& trajectory, const TaskLoss& loss,
                                               const ParameterSet& parameters,
                                               const StepProgress& progress) {
  if (settings_.accuracy <= 0.0 || settings_.method == "direct")
    return backpropagate(trajectory, loss, parameters, settings_, progress, 1);
  AdjointSolverStats costs;
  double seconds = 0.0;
  double looseTolerance = start_;
  GradientResult loose = pass(trajectory, loss, parameters, settings_, looseTolerance, progress, 1);
  addSolverCosts(costs, loose.solver);
  seconds += loose.seconds;
  int passes = 1;
  for (;;) {
    const double tightTolerance = looseTolerance / kToleranceStep >= kTightestTolerance
                                      ? looseTolerance / kToleranceStep
                                      : 0.0;  // 0: direct
    GradientResult tight =
        pass(trajectory, loss, parameters, settings_, tightTolerance, progress, passes + 1);
    ++passes;
    addSolverCosts(costs, tight.solver);
    seconds += tight.seconds;
    GradientErrorEstimate e = difference(loose, tight, tightTolerance, settings_.accuracy);
    if (e.met || tightTolerance == 0.0) {
      // Remember the pair (or, missed, the last one tried). Never looser again: the error
      // does not scale with the tolerance in any fixed way (on the 24^2 soft napkin 100 times
      // the tolerance is 3,000 times the error), so nothing known says a looser pair would do.
      start_ = looseTolerance;
      e.passes = passes;
      e.tolerance = tightTolerance;
      const AdjointSolverStats own = tight.solver;
      tight.solver = costs;
      tight.solver.maxResidual = own.maxResidual;
      tight.solver.adjointGrowth = own.adjointGrowth;
      tight.seconds = seconds;
      tight.error = e;
      return tight;
    }
    loose = std::move(tight);
    looseTolerance = tightTolerance;
  }
}

GradientResult backpropagateToAccuracy(const Trajectory& trajectory, const TaskLoss& loss,
                                       const ParameterSet& parameters,
                                       const BackwardSettings& settings) {
  return AccurateBackward(settings).differentiate(trajectory, loss, parameters);
}

std::string describeGradientError(const GradientErrorEstimate& error) {
  char text[200];
  if (error.basis == "difference") {
    char against[40];
    if (error.tolerance > 0.0)
      std::snprintf(against, sizeof against, "%.2g against %.2g", error.tolerance,
                    error.tolerance * kToleranceStep);
    else
      std::snprintf(against, sizeof against, "direct against the tightest iterative");
    std::snprintf(text, sizeof text,
                  "gradient error %.2g (tolerance %s; %d passes; accuracy %.2g %s)", error.relative,
                  against, error.passes, error.requested, error.met ? "met" : "MISSED");
  } else if (error.basis == "round-off") {
    std::snprintf(text, sizeof text, "gradient error %.2g (direct: round-off size, 1 pass)",
                  error.relative);
  } else {
    std::snprintf(text, sizeof text,
                  "gradient error %.2g (tolerance %.2g; fit from the growth, 1 pass; accuracy "
                  "control off)",
                  error.relative, error.tolerance);
  }
  return text;
}

std::string gradientErrorWarning(const GradientErrorEstimate& error) {
  char text[480];
  if (error.requested > 0.0) {
    if (error.met) return "";
    std::snprintf(text, sizeof text,
                  "backward: the gradient's estimated relative error %.2g misses the requested "
                  "%.2g (solver.backward.accuracy) even against the direct sparse LU (%d passes): "
                  "the adjoint's growth amplifies round-off; the gradient is as good as this run "
                  "allows",
                  error.relative, error.requested, error.passes);
    return text;
  }
  if (!(error.relative >= kAdjointGradientErrorWarning) || error.basis == "round-off") return "";
  std::snprintf(text, sizeof text,
                "backward: the gradient may be off by about %.1g (relative; %s estimate, "
                "solver.backward.accuracy 0 turns the error control off): set "
                "solver.backward.accuracy to have it checked and met",
                error.relative, error.basis.c_str());
  return text;
}

}  // namespace weft
