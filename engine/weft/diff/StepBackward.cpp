#include <weft/diff/StepBackward.h>

#include <weft/core/Error.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/ContactAdjoint.h>
#include <weft/diff/ParameterPartials.h>
#include <weft/physics/Model.h>

#include <chrono>
#include <stdexcept>

namespace weft {

// What one step's adjoint needs of a model (DiffCloth Eqs. 19, 29): P's factor and Delta P, the
// parameters' partials, the contact law's Jacobians. One per dt: the scene's, and the finer ones
// of the pieces adaptive time stepping split steps into.
struct StepBackward::Piece {
  Piece(const std::shared_ptr<const Model>& model, const ParameterSet& parameters, bool contacts)
      : system(model), partials(*model, parameters.parameters()), h(model->dt()) {
    if (contacts) contact = std::make_unique<ContactAdjoint>(*model);
  }
  AdjointSystem system;
  ParameterPartials partials;
  std::unique_ptr<ContactAdjoint> contact;
  double h;
};

StepBackward::StepBackward(const Trajectory& trajectory, const ParameterSet& parameters,
                           const BackwardSettings& settings)
    : trajectory_(trajectory), parameters_(parameters), contacts_(!trajectory.contacts.empty()) {
  if (!trajectory.model)
    throw std::invalid_argument(
        "backpropagate: the trajectory has no model (record it with Simulator::run)");
  // The impact-zone response (Liang 2019 Sec. 3.4) has no adjoint here yet: a gradient that
  // ignored it would be the gradient of another simulation, so none is given.
  const Scene& scene = trajectory.model->scene();
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    if (scene.cloths[c].selfCollision && scene.cloths[c].selfCollision->impactZones)
      throw InputError(scene.file, "cloths." + std::to_string(c) + ".self_collision.model",
                       "gradients through impact zones are not implemented yet; use the \"node\" "
                       "model for a differentiable run");
  whole_ = std::make_unique<Piece>(trajectory.model, parameters, contacts_);
  solver_ = std::make_unique<AdjointSolver>(settings);
  const int m = trajectory.model->cloth().nodeCount();
  for (NodeMatrix* b :
       {&rhs_, &z_, &wbar_, &dLdv_, &forceLike_, &dLdxPiece_, &dLdxPieceNext_, &dLdvNext_})
    b->setZero(m, 3);
}

StepBackward::~StepBackward() = default;

const AdjointSolverStats& StepBackward::stats() const {
  return solver_->stats();
}

double StepBackward::adjointGrowth() const {
  return growth_.factor();
}

StepBackward::Piece& StepBackward::pieceFor(const std::shared_ptr<const Model>& model) {
  auto& piece = pieces_[model.get()];
  if (!piece) piece = std::make_unique<Piece>(model, parameters_, contacts_);
  return *piece;
}

// One step (or piece) x0, v0 -> x1 ending at t1: from dL/dx1 (dLdx1) and dL/dv1 (dLdvNext_),
// adds the step's terms to dL/dx0 (dLdx0) and the gradient, and leaves dL/dv0 in dLdvNext_.
void StepBackward::backStep(Piece& a, const NodeMatrix& x0, const NodeMatrix& v0,
                            const NodeMatrix& x1, double t1, const StepContacts* stepContacts,
                            const NodeMatrix& dLdx1, NodeMatrix& dLdx0, int state,
                            Eigen::VectorXd& gradient) {
  const ClothModel& model = trajectory_.model->cloth();
  const double h = a.h;
  rhs_ = dLdx1 + dLdvNext_ / h;
  const bool touching = a.contact && stepContacts && !stepContacts->points.empty();
  const auto prepareStart = std::chrono::steady_clock::now();
  if (touching) a.contact->prepare(*stepContacts, x0, t1 - h, t1, state);
  const auto contactDone = std::chrono::steady_clock::now();
  a.system.prepare(x1, touching ? a.contact.get() : nullptr);
  deltaRSeconds_ += std::chrono::duration<double>(contactDone - prepareStart).count();
  deltaPSeconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - contactDone).count();
  solver_->solve(a.system, rhs_, z_, state);
  growth_.observe(z_);
  // wbar = R'^T z: what the contact impulses pass on of z (zero without contact).
  if (a.system.hasContact())
    a.contact->applyTransposed(z_, wbar_, y_);
  else
    wbar_.setZero();
  // Force-like parameters enter f as well as G1: their partials take S^T z = z + wbar.
  forceLike_ = z_ + wbar_;
  a.partials.accumulate(x0, v0, x1, t1, forceLike_, gradient);
  if (handleSink_) {
    const std::vector<HandleGroup>& handles = trajectory_.model->handles();
    for (std::size_t g = 0; g < handles.size(); ++g)
      for (int j : handles[g].nodes)
        handleSink_->row(static_cast<Eigen::Index>(g)) +=
            h * h * handles[g].stiffness * forceLike_.row(j);
  }
  dLdx0 += model.mass.asDiagonal() * z_ - dLdvNext_ / h;
  // Projections set from x_n enter the step like a force (b, and through it f): S^T z.
  if (a.system.dependsOnStart()) a.system.addStartGradient(x0, forceLike_, dLdx0);
  dLdv_ = h * (model.mass.asDiagonal() * forceLike_);  // dG/dv_n = -h M, df/dv_n = M
  if (a.system.hasContact()) {
    a.contact->addStateGradients(y_, dLdx0, dLdv_);
    a.contact->addParameterGradients(parameters_.parameters(), y_, wbar_, x0, v0, x1, gradient);
  }
  dLdvNext_ = dLdv_;
}

void StepBackward::step(int n, const NodeMatrix& dLdx1, const NodeMatrix& dLdv1, NodeMatrix& dLdx0,
                        NodeMatrix& dLdv0, Eigen::VectorXd& gradient,
                        NodeMatrix* dLdHandleOffsets) {
  const Trajectory& t = trajectory_;
  if (n < 0 || n >= t.stepCount())
    throw std::invalid_argument("StepBackward::step: no step " + std::to_string(n));
  if (dLdHandleOffsets &&
      (dLdHandleOffsets->rows() != static_cast<Eigen::Index>(t.model->handles().size())))
    throw std::invalid_argument("StepBackward::step: dLdHandleOffsets needs one row per handle");
  handleSink_ = dLdHandleOffsets;
  dLdvNext_ = dLdv1;
  const std::vector<Substep>* split =
      n < static_cast<int>(t.substeps.size()) && !t.substeps[n].empty() ? &t.substeps[n] : nullptr;
  if (!split) {
    backStep(*whole_, t.positions[n], t.velocities[n], t.positions[n + 1], t.steps[n].time,
             contacts_ ? &t.contacts[n] : nullptr, dLdx1, dLdx0, n + 1, gradient);
  } else {
    // A step adaptive time stepping split: its pieces in reverse, each with its own dt; the
    // states between them are the pieces' own (dLdxPiece_).
    const int count = static_cast<int>(split->size());
    for (int k = count - 1; k >= 0; --k) {
      const Substep& piece = (*split)[static_cast<std::size_t>(k)];
      if (k + 1 < count) dLdxPieceNext_.swap(dLdxPiece_);  // the later piece's dL/dx0
      NodeMatrix& into = k == 0 ? dLdx0 : dLdxPiece_;
      if (k > 0) dLdxPiece_.setZero();
      backStep(pieceFor(piece.model), piece.x0, piece.v0, piece.x1, piece.time,
               contacts_ ? &piece.contacts : nullptr, k + 1 == count ? dLdx1 : dLdxPieceNext_, into,
               n + 1, gradient);
    }
  }
  dLdv0 = dLdvNext_;
  handleSink_ = nullptr;
}

void StepBackward::addInitial(const NodeMatrix& dLdv0, Eigen::VectorXd& gradient) const {
  whole_->partials.accumulateInitial(dLdv0, gradient);
}

}  // namespace weft
