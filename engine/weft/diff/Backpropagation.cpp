#include <weft/diff/Backpropagation.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/ParameterPartials.h>

#include <chrono>

namespace weft {

void requireContactFree(const Scene& scene) {
  const char* what = "gradients through contact are not yet supported (DiffCloth Sec. 4.2 is the next step)";
  if (!scene.obstacles.empty()) throw InputError(scene.file, "obstacles", what);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    if (scene.cloths[c].selfCollision)
      throw InputError(scene.file, "cloths." + std::to_string(c) + ".self_collision", what);
}

GradientResult backpropagate(const Scene& scene, const Trajectory& trajectory, const TaskLoss& loss,
                             const ParameterSet& parameters, const BackwardSettings& settings) {
  requireContactFree(scene);
  const auto start = std::chrono::steady_clock::now();
  GradientResult result;
  result.loss = loss.value(trajectory);
  result.gradient = Eigen::VectorXd::Zero(parameters.size());

  AdjointSystem system(scene);
  const ClothModel& model = system.model();
  ParameterPartials partials(scene, model, parameters.parameters());
  AdjointSolver solver(settings);
  const double h = scene.time.dt;
  const int steps = trajectory.stepCount();
  const int m = model.nodeCount();

  std::vector<NodeMatrix> dLdx = loss.gradient(trajectory);
  NodeMatrix dLdvNext = NodeMatrix::Zero(m, 3);  // dL/dv_{n+1} through the steps after n+1
  NodeMatrix rhs(m, 3), z(m, 3);
  for (int n = steps - 1; n >= 0; --n) {
    const NodeMatrix& x1 = trajectory.positions[n + 1];
    rhs = dLdx[n + 1] + dLdvNext / h;
    system.prepare(x1);
    solver.solve(system, rhs, z, n + 1);
    partials.accumulate(trajectory.positions[n], trajectory.velocities[n], x1, trajectory.steps[n].time, z,
                        result.gradient);
    const NodeMatrix massZ = model.mass.asDiagonal() * z;
    dLdx[n] += massZ - dLdvNext / h;
    dLdvNext = h * massZ;
  }
  result.dLdx0 = dLdx[0];
  result.dLdv0 = dLdvNext;
  partials.accumulateInitial(result.dLdv0, result.gradient);
  result.solver = solver.stats();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace weft
