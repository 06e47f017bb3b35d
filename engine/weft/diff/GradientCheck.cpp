#include <weft/diff/GradientCheck.h>

#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/TaskLoss.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace weft {

double relativeError(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0.0 ? std::abs(a - b) / scale : 0.0;
}

double GradientCheckReport::maxRelativeError() const {
  double worst = 0.0;
  for (const auto& e : entries) worst = std::max(worst, e.relativeError);
  return worst;
}

TightAdjointGradient tightAdjointGradient(const Scene& input, const ParameterSet& parameters,
                                          const GradientCheckOptions& options) {
  TightAdjointGradient out;
  out.scene = withTightForwardSolver(input, options.forwardTolerance);
  const TaskLoss loss(out.scene);  // before the forward run: a bad task fails early
  out.backward = out.scene.solver.backward;
  if (options.backwardMethod) out.backward.method = *options.backwardMethod;
  out.backward.tolerance = options.backwardTolerance;
  const ForwardPass base = runForwardPass(out.scene);
  out.unconvergedSteps = base.unconvergedSteps;
  out.result = backpropagateToAccuracy(base.trajectory, loss, parameters, out.backward);
  return out;
}

GradientCheckReport checkGradient(const Scene& input, const ParameterSet& parameters,
                                  const GradientCheckOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const TightAdjointGradient tight = tightAdjointGradient(input, parameters, options);
  const Scene& scene = tight.scene;
  const GradientResult& adjoint = tight.result;
  const TaskLoss loss(scene);

  GradientCheckReport report;
  report.backwardMethod = tight.backward.method;
  report.backwardTolerance = tight.backward.tolerance;
  ++report.forwardRuns;
  report.unconvergedSteps += tight.unconvergedSteps;
  report.loss = adjoint.loss;
  report.backward = adjoint.solver;
  report.error = adjoint.error;

  const Eigen::VectorXd values = parameters.values(scene);
  for (int k = 0; k < parameters.size(); ++k) {
    GradientCheckEntry e;
    e.param = parameters[k].path;
    e.value = values[k];
    e.step = values[k] != 0.0 ? options.eps * std::abs(values[k]) : options.eps;
    double side[2];
    for (int s = 0; s < 2; ++s) {
      Eigen::VectorXd shifted = values;
      shifted[k] += s == 0 ? e.step : -e.step;
      const ForwardPass run = runForwardPass(parameters.compile(scene, shifted));
      ++report.forwardRuns;
      report.unconvergedSteps += run.unconvergedSteps;
      side[s] = loss.value(run.trajectory.model->scene(), run.trajectory);
    }
    e.finiteDifference = (side[0] - side[1]) / (2.0 * e.step);
    e.adjoint = adjoint.gradient[k];
    e.errorEstimate = adjoint.error.absolute[k];
    e.relativeError = relativeError(e.adjoint, e.finiteDifference);
    report.entries.push_back(e);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace weft
