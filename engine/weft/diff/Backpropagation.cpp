#include <weft/diff/Backpropagation.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointGrowth.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/ParameterPartials.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

namespace weft {

namespace {

// What one step's adjoint needs of a model (DiffCloth Eqs. 19, 29): P's factor and Delta P, the
// parameters' partials, the contact law's Jacobians. One per dt: the scene's, and the finer ones
// of the pieces adaptive time stepping split steps into.
struct StepAdjoint {
  StepAdjoint(const std::shared_ptr<const Model>& model, const ParameterSet& parameters,
              bool contacts)
      : system(model), partials(*model, parameters.parameters()), h(model->dt()) {
    if (contacts) contact = std::make_unique<ContactAdjoint>(*model);
  }
  AdjointSystem system;
  ParameterPartials partials;
  std::unique_ptr<ContactAdjoint> contact;
  double h;
};

}  // namespace

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

  const bool contacts = !trajectory.contacts.empty();
  StepAdjoint whole(trajectory.model, parameters, contacts);
  std::map<const Model*, std::unique_ptr<StepAdjoint>> pieces;  // by the pieces' models
  const ClothModel& model = compiled.cloth();
  AdjointSolver solver(settings);
  const int steps = trajectory.stepCount();
  const int m = model.nodeCount();

  std::vector<NodeMatrix> dLdx = loss.gradient(trajectory);
  NodeMatrix dLdvNext = NodeMatrix::Zero(m, 3);  // dL/dv_{n+1} through the steps after n+1
  NodeMatrix rhs(m, 3), z = NodeMatrix::Zero(m, 3), wbar = NodeMatrix::Zero(m, 3), dLdv(m, 3);
  NodeMatrix forceLike(m, 3);  // S^T z = z + wbar
  NodeMatrix dLdxPiece(m, 3);  // dL/dx at a state between a split step's pieces
  Eigen::MatrixX3d y;
  AdjointGrowth growth;
  // One step (or piece) x0, v0 -> x1 ending at t1: from dL/dx1 (dLdx1) and dL/dv1 (dLdvNext),
  // adds the step's terms to dL/dx0 (dLdx0) and the gradient, and leaves dL/dv0 in dLdvNext.
  auto backStep = [&](StepAdjoint& a, const NodeMatrix& x0, const NodeMatrix& v0,
                      const NodeMatrix& x1, double t1, const StepContacts* stepContacts,
                      const NodeMatrix& dLdx1, NodeMatrix& dLdx0, int state) {
    const double h = a.h;
    rhs = dLdx1 + dLdvNext / h;
    const bool touching = a.contact && stepContacts && !stepContacts->points.empty();
    const auto prepareStart = std::chrono::steady_clock::now();
    if (touching) a.contact->prepare(*stepContacts, x0, t1 - h, t1, state);
    const auto contactDone = std::chrono::steady_clock::now();
    a.system.prepare(x1, touching ? a.contact.get() : nullptr);
    result.deltaRSeconds += std::chrono::duration<double>(contactDone - prepareStart).count();
    result.deltaPSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - contactDone).count();
    solver.solve(a.system, rhs, z, state);
    growth.observe(z);
    // wbar = R'^T z: what the contact impulses pass on of z (zero without contact).
    if (a.system.hasContact())
      a.contact->applyTransposed(z, wbar, y);
    else
      wbar.setZero();
    // Force-like parameters enter f as well as G1: their partials take S^T z = z + wbar.
    forceLike = z + wbar;
    a.partials.accumulate(x0, v0, x1, t1, forceLike, result.gradient);
    dLdx0 += model.mass.asDiagonal() * z - dLdvNext / h;
    // Projections set from x_n enter the step like a force (b, and through it f): S^T z.
    if (a.system.dependsOnStart()) a.system.addStartGradient(x0, forceLike, dLdx0);
    dLdv = h * (model.mass.asDiagonal() * forceLike);  // dG/dv_n = -h M, df/dv_n = M
    if (a.system.hasContact()) {
      a.contact->addStateGradients(y, dLdx0, dLdv);
      a.contact->addParameterGradients(parameters.parameters(), y, wbar, x0, v0, x1,
                                       result.gradient);
    }
    dLdvNext = dLdv;
  };
  for (int n = steps - 1; n >= 0; --n) {
    const std::vector<Substep>* split =
        n < static_cast<int>(trajectory.substeps.size()) && !trajectory.substeps[n].empty()
            ? &trajectory.substeps[n]
            : nullptr;
    if (!split) {
      backStep(whole, trajectory.positions[n], trajectory.velocities[n],
               trajectory.positions[n + 1], trajectory.steps[n].time,
               contacts ? &trajectory.contacts[n] : nullptr, dLdx[n + 1], dLdx[n], n + 1);
      continue;
    }
    // A step adaptive time stepping split: its pieces in reverse, each with its own dt.
    for (int k = static_cast<int>(split->size()) - 1; k >= 0; --k) {
      const Substep& piece = (*split)[static_cast<std::size_t>(k)];
      auto& adjoint = pieces[piece.model.get()];
      if (!adjoint) adjoint = std::make_unique<StepAdjoint>(piece.model, parameters, contacts);
      const NodeMatrix dLdx1 = k + 1 == static_cast<int>(split->size()) ? dLdx[n + 1] : dLdxPiece;
      NodeMatrix& dLdx0 = k == 0 ? dLdx[n] : dLdxPiece;
      if (k > 0) dLdxPiece.setZero();
      backStep(*adjoint, piece.x0, piece.v0, piece.x1, piece.time,
               contacts ? &piece.contacts : nullptr, dLdx1, dLdx0, n + 1);
    }
  }
  result.dLdx0 = dLdx[0];
  result.dLdv0 = dLdvNext;
  result.dLdx = std::move(dLdx);  // already computed: keeping it costs nothing
  whole.partials.accumulateInitial(result.dLdv0, result.gradient);
  // Terms of the parameters themselves (the handles' clearance): no state in between.
  loss.addParameterGradient(scene, parameters.parameters(), result.gradient);
  result.solver = solver.stats();
  result.solver.adjointGrowth = growth.factor();
  result.error = singlePassErrorEstimate(result, settings);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace weft
