#include <weft/diff/SceneGradient.h>

#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/TaskLoss.h>

#include <chrono>

namespace weft {

SceneGradient sceneGradient(const Scene& scene, const ParameterSet& parameters) {
  const TaskLoss loss(scene);  // before the forward run: a bad task fails early
  SceneGradient out;
  out.values = parameters.values(scene);
  const auto start = std::chrono::steady_clock::now();
  // As SimulationObjective::evaluate compiles it: the parameters written into the scene.
  const ForwardPass forward = runForwardPass(parameters.compile(scene, out.values));
  out.forwardSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.unconvergedSteps = forward.unconvergedSteps;
  out.result = backpropagateToAccuracy(forward.trajectory, loss, parameters,
                                       forward.trajectory.model->solver().backward);
  return out;
}

}  // namespace weft
