#include <weft/optim/SimulationObjective.h>

#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>

#include <algorithm>
#include <chrono>

namespace weft {

namespace {
const Scene& checked(const Scene& scene) {
  requireContactFree(scene);
  return scene;
}
}  // namespace

SimulationObjective::SimulationObjective(const Scene& scene, const ParameterSet& parameters)
    : scene_(checked(scene)), parameters_(parameters), space_(scene, parameters), loss_(scene) {}

double SimulationObjective::evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& gradient) {
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = parameters_.withValues(scene_, space_.toValues(z));
  const ForwardPass forward = runForwardPass(scene);
  unconverged_ += forward.unconvergedSteps;
  const GradientResult r = backpropagate(scene, forward.trajectory, loss_, parameters_, scene.solver.backward);
  gradient = space_.gradientToCoordinates(z, r.gradient);
  backward_.solves += r.solver.solves;
  backward_.iterations += r.solver.iterations;
  backward_.maxIterations = std::max(backward_.maxIterations, r.solver.maxIterations);
  backward_.notConverged += r.solver.notConverged;
  backward_.diverged += r.solver.diverged;
  backward_.fallbacks += r.solver.fallbacks;
  backward_.maxResidual = std::max(backward_.maxResidual, r.solver.maxResidual);
  backward_.seconds += r.solver.seconds;
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r.loss;
}

}  // namespace weft
