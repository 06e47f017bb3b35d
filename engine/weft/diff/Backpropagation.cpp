#include <weft/diff/Backpropagation.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointGrowth.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/StepBackward.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace weft {

GradientErrorEstimate singlePassErrorEstimate(const GradientResult& result,
                                              const BackwardSettings& settings) {
  GradientErrorEstimate e;
  const double growth = std::max(result.solver.adjointGrowth, 1.0);
  if (settings.method == "direct") {
    e.relative = std::numeric_limits<double>::epsilon() * growth;
    e.basis = "round-off";
  } else {
    e.relative = adjointGradientErrorEstimate(growth, settings.tolerance);
    e.tolerance = settings.tolerance;
    e.basis = "fit";
  }
  const double norm = result.gradient.norm();
  if (norm == 0.0) e.relative = 0.0;
  // A component's error is at most the vector's: relative * |g|.
  e.absolute = Eigen::VectorXd::Constant(result.gradient.size(), e.relative * norm);
  return e;
}

GradientResult backpropagate(const Trajectory& trajectory, const TaskLoss& loss,
                             const ParameterSet& parameters, const BackwardSettings& settings,
                             const StepProgress& progress, int pass) {
  const auto start = std::chrono::steady_clock::now();
  StepBackward back(trajectory, parameters, settings);  // throws for a trajectory without model
  const Scene& scene = trajectory.model->scene();
  GradientResult result;
  result.loss = loss.value(scene, trajectory);
  result.gradient = Eigen::VectorXd::Zero(parameters.size());
  const int m = trajectory.model->cloth().nodeCount();
  std::vector<NodeMatrix> dLdx = loss.gradient(trajectory);
  NodeMatrix dLdvNext = NodeMatrix::Zero(m, 3);  // dL/dv_{n+1} through the steps after n+1
  NodeMatrix dLdv(m, 3);
  const int steps = trajectory.stepCount();
  for (int n = steps - 1; n >= 0; --n) {
    back.step(n, dLdx[n + 1], dLdvNext, dLdx[n], dLdv, result.gradient);
    dLdvNext.swap(dLdv);
    if (progress) progress(PassPhase::Backward, pass, steps - n, steps);
  }
  result.dLdx0 = dLdx[0];
  result.dLdv0 = dLdvNext;
  result.dLdx = std::move(dLdx);  // already computed: keeping it costs nothing
  back.addInitial(result.dLdv0, result.gradient);
  // Terms of the parameters themselves (the handles' clearance): no state in between.
  loss.addParameterGradient(scene, parameters.parameters(), result.gradient);
  result.solver = back.stats();
  result.solver.adjointGrowth = back.adjointGrowth();
  result.deltaPSeconds = back.deltaPSeconds();
  result.deltaRSeconds = back.deltaRSeconds();
  result.error = singlePassErrorEstimate(result, settings);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace weft
