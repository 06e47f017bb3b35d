#include <weft/diff/Backpropagation.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointGrowth.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/ParameterPartials.h>

#include <chrono>
#include <memory>
#include <stdexcept>

namespace weft {

GradientResult backpropagate(const Trajectory& trajectory, const TaskLoss& loss,
                             const ParameterSet& parameters, const BackwardSettings& settings) {
  if (!trajectory.model)
    throw std::invalid_argument(
        "backpropagate: the trajectory has no model (record it with Simulator::run)");
  const auto start = std::chrono::steady_clock::now();
  const Model& compiled = *trajectory.model;
  const Scene& scene = compiled.scene();
  GradientResult result;
  result.loss = loss.value(scene, trajectory);
  result.gradient = Eigen::VectorXd::Zero(parameters.size());

  AdjointSystem system(trajectory.model);
  const ClothModel& model = compiled.cloth();
  ParameterPartials partials(compiled, parameters.parameters());
  AdjointSolver solver(settings);
  const double h = compiled.dt();
  const int steps = trajectory.stepCount();
  const int m = model.nodeCount();

  // Contact steps (ContactAdjoint.h): the law's Jacobians and frames from the recorded contacts.
  std::unique_ptr<ContactAdjoint> contact;
  if (!trajectory.contacts.empty()) contact = std::make_unique<ContactAdjoint>(compiled);

  std::vector<NodeMatrix> dLdx = loss.gradient(trajectory);
  NodeMatrix dLdvNext = NodeMatrix::Zero(m, 3);  // dL/dv_{n+1} through the steps after n+1
  NodeMatrix rhs(m, 3), z = NodeMatrix::Zero(m, 3), wbar = NodeMatrix::Zero(m, 3), dLdv(m, 3);
  NodeMatrix forceLike(m, 3);  // S^T z = z + wbar
  Eigen::MatrixX3d y;
  AdjointGrowth growth;
  for (int n = steps - 1; n >= 0; --n) {
    const NodeMatrix& x0 = trajectory.positions[n];
    const NodeMatrix& v0 = trajectory.velocities[n];
    const NodeMatrix& x1 = trajectory.positions[n + 1];
    const double t1 = trajectory.steps[n].time;
    rhs = dLdx[n + 1] + dLdvNext / h;
    const bool touching = contact && !trajectory.contacts[n].points.empty();
    const auto prepareStart = std::chrono::steady_clock::now();
    if (touching) contact->prepare(trajectory.contacts[n], x0, t1 - h, t1, n + 1);
    const auto contactDone = std::chrono::steady_clock::now();
    system.prepare(x1, touching ? contact.get() : nullptr);
    result.deltaRSeconds += std::chrono::duration<double>(contactDone - prepareStart).count();
    result.deltaPSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - contactDone).count();
    solver.solve(system, rhs, z, n + 1);
    growth.observe(z);
    // wbar = R'^T z: what the contact impulses pass on of z (zero without contact).
    if (system.hasContact())
      contact->applyTransposed(z, wbar, y);
    else
      wbar.setZero();
    // Force-like parameters enter f as well as G1: their partials take S^T z = z + wbar.
    forceLike = z + wbar;
    partials.accumulate(x0, v0, x1, t1, forceLike, result.gradient);
    dLdx[n] += model.mass.asDiagonal() * z - dLdvNext / h;
    // Projections set from x_n enter the step like a force (b, and through it f): S^T z.
    if (system.dependsOnStart()) system.addStartGradient(x0, forceLike, dLdx[n]);
    dLdv = h * (model.mass.asDiagonal() * forceLike);  // dG/dv_n = -h M, df/dv_n = M
    if (system.hasContact()) {
      contact->addStateGradients(y, dLdx[n], dLdv);
      contact->addParameterGradients(parameters.parameters(), y, wbar, x0, v0, x1, result.gradient);
    }
    dLdvNext = dLdv;
  }
  result.dLdx0 = dLdx[0];
  result.dLdv0 = dLdvNext;
  result.dLdx = std::move(dLdx);  // already computed: keeping it costs nothing
  partials.accumulateInitial(result.dLdv0, result.gradient);
  // Terms of the parameters themselves (the handles' clearance): no state in between.
  loss.addParameterGradient(scene, parameters.parameters(), result.gradient);
  result.solver = solver.stats();
  result.solver.adjointGrowth = growth.factor();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace weft
