#include <weft/physics/Simulator.h>

#include <weft/contact/FrictionalContact.h>
#include <weft/core/Error.h>
#include <weft/physics/ExternalForce.h>
#include <weft/physics/ModuleTimer.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/StepContext.h>
#include <weft/physics/StepSolver.h>
#include <weft/physics/SystemMatrix.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace weft {
namespace {

// Times a step is solved again with contacts its solved path violated and detection missed
// (step()).
constexpr int kMissedContactPasses = 2;

// A speed no cloth reaches unless the integration has blown up.
constexpr double kBlowUpSpeed = 1e5;  // m/s

}  // namespace

Simulator::Simulator(const Scene& scene) : Simulator(Model::compile(scene)) {}

Simulator::Simulator(std::shared_ptr<const Model> model)
    : compiled_(std::move(model)),
      scene_(compiled_->scene()),
      model_(compiled_->cloth()),
      h_(compiled_->dt()),
      timer_(std::make_unique<ModuleTimer>()) {
  // Modules: the solver, then only what the scene names (the model's constraint families with
  // rows, its forces, contact for obstacles or self-collision).
  solverModule_ = timer_->add("solver");
  constraints_ = compiled_->instantiateConstraints();
  for (const auto& c : constraints_) constraintModule_.push_back(timer_->add(c->name()));
  for (const auto& f : compiled_->forces()) forceModule_.push_back(timer_->add(f->name()));

  if (compiled_->hasContact()) {
    const auto start = ModuleTimer::Clock::now();
    contact_ = std::make_unique<FrictionalContact>(scene_, model_, compiled_->obstacleShapes());
    if (contact_->hasObstacles()) contactDetectionModule_ = timer_->add("contact_detection");
    if (contact_->hasSelfCollision()) selfCollisionModule_ = timer_->add("self_collision");
    contactSolveModule_ = timer_->add("contact_solve");
    // Building the self-collision tables counts as detection.
    timer_->charge(contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_,
                   ModuleTimer::secondsSince(start));
  }

  const int m = model_.nodeCount();
  x_ = model_.rest.vertices;
  v_ = compiled_->initialVelocities();
  warmStart_.setZero(m, 3);
  force_.setZero(m, 3);
  if (contact_) predicted_.setZero(m, 3);

  timer_->timed(solverModule_,
                [&] { system_ = std::make_unique<SystemMatrix>(model_.mass, constraints_, h_); });
  context_ =
      std::make_unique<StepContext>(*compiled_, x_, constraints_, constraintModule_, *system_,
                                    *timer_, solverModule_, contact_.get(), contactSolveModule_);
  solver_ = makeStepSolver(*context_);
}

Simulator::~Simulator() = default;

const std::vector<std::string>& Simulator::moduleNames() const {
  return timer_->names();
}
const std::vector<double>& Simulator::moduleSeconds() const {
  return timer_->seconds();
}
const Eigen::SparseMatrix<double>& Simulator::systemMatrix() const {
  return system_->matrix();
}

const StepStats& Simulator::step() {
  const double h2 = h_ * h_;
  const double t1 = time_ + h_;
  const SolverSettings& solver = scene_.solver;
  StepContext& ctx = *context_;
  StepStats& stats = ctx.stats;
  stats = StepStats{};
  stats.step = step_ + 1;
  stats.time = t1;
  timer_->beginStep();
  ctx.solveLimit = solver.pdIterations;

  // External forces at the end of the step (implicit Euler, Eqs. 1-2).
  force_.setZero();
  const auto& forces = compiled_->forces();
  for (std::size_t f = 0; f < forces.size(); ++f)
    timer_->timed(forceModule_[f], [&] { forces[f]->accumulate(t1, force_); });
  for (std::size_t c = 0; c < constraints_.size(); ++c)
    timer_->timed(constraintModule_[c], [&] { constraints_[c]->beginStep(t1, x_); });

  timer_->timed(solverModule_, [&] {
    // y = x_n + h v_n + h^2 M^{-1} f_ext (Eq. 3)
    ctx.y = x_ + h_ * v_ + h2 * (ctx.inverseMass.asDiagonal() * force_);
    ctx.massY = model_.mass.asDiagonal() * ctx.y;
    // Warm start: the displacement the internal forces caused last step (x_n - y_{n-1}) changes
    // slowly, and carries the slow, bending-like modes that PD is slowest to converge.
    ctx.iterate = ctx.y + warmStart_;
  });

  if (contact_) {
    detectContacts(time_, t1);
    solver_->solve(ctx);
    // Detection saw the predicted path only (DiffCloth Eq. 9's frames from x_n, v_n); where the
    // path the solve took strays from it, contacts it meets that the set lacks are added and the
    // step is solved again from its result, each pass with a fresh iteration budget.
    for (int pass = 0; pass < kMissedContactPasses && solver_->resolvesMissedContacts(); ++pass) {
      int added = 0;
      timer_->timed(contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_,
                    [&] {
                      ctx.change = ctx.global - x_;
                      added = contact_->addMissedContacts(x_, predicted_, ctx.change);
                    });
      if (added == 0) break;
      stats.lateContacts += added;
      timer_->timed(contactSolveModule_, [&] { solver_->prepareContacts(ctx); });
      timer_->timed(solverModule_, [&] { ctx.iterate = ctx.global; });
      ctx.solveLimit = stats.pdIterations + solver.pdIterations;
      solver_->solve(ctx);
    }
    timer_->timed(contactSolveModule_, [&] {
      solver_->record(ctx, lastContacts_);
      countBranches(lastContacts_, stats);
      lastContacts_.sweeps = stats.contactSweeps;
    });
    // The recorded impulses feed the output (contact_forces.npy) and the backward pass.
    for (const ContactPoint& p : lastContacts_.points)
      if (!p.impulse.allFinite() || !p.velocity.allFinite())
        throw NumericalError(
            step_ + 1, "contact_solve",
            "non-finite contact impulse or velocity at node " + std::to_string(p.node));
  } else {
    solver_->solve(ctx);
  }
  // The last global solution is the step's result (one PD iteration past the checked iterate).
  if (!ctx.global.allFinite()) diagnoseNonFinite(x_);
  if (contact_ && contact_->hasObstacles())
    timer_->timed(contactDetectionModule_,
                  [&] { stats.depth = contact_->deepestPenetration(ctx.global); });
  stats.moduleSeconds = timer_->stepSeconds();
  v_ = (ctx.global - x_) / h_;
  x_ = ctx.global;
  warmStart_ = x_ - ctx.y;
  time_ = t1;
  ++step_;
  const double maxSpeed = std::sqrt(v_.rowwise().squaredNorm().maxCoeff());
  if (!(maxSpeed < kBlowUpSpeed))
    throw NumericalError(step_, "solver",
                         "velocity " + std::to_string(maxSpeed) + " m/s: the integration blew up");
  return stats;
}

void Simulator::detectContacts(double t0, double t1) {
  // The contact set and frames are found once per step from x_n and the predicted motion (the
  // warm-started first iterate), and stay frozen during the iterations: the explicit J_n(x_n,
  // v_n) of DiffCloth Eq. 9; after the solve, step() adds contacts the path taken violated and
  // the predicted one missed (FrictionalContact::addMissedContacts).
  const int first = contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_;
  timer_->timed(first, [&] {
    contact_->beginStep(t0, t1);
    predicted_ = context_->iterate - x_;
  });
  if (contact_->hasObstacles())
    timer_->timed(contactDetectionModule_, [&] { contact_->detectObstacles(x_, predicted_); });
  if (contact_->hasSelfCollision())
    timer_->timed(selfCollisionModule_, [&] { contact_->detectSelfCollisions(x_, predicted_); });
  timer_->timed(contactSolveModule_, [&] { solver_->prepareContacts(*context_); });
}

void Simulator::restart(int step, const NodeMatrix& x, const NodeMatrix& v) {
  if (x.rows() != x_.rows() || v.rows() != v_.rows() || step < 0)
    throw std::invalid_argument(
        "Simulator::restart: the state must have one row per node and step >= 0");
  x_ = x;
  v_ = v;
  step_ = step;
  time_ = step * h_;
  warmStart_.setZero();
}

void Simulator::diagnoseNonFinite(const NodeMatrix& lastGood) const {
  NodeMatrix f = NodeMatrix::Zero(lastGood.rows(), 3);
  for (const auto& force : compiled_->forces()) {
    force->accumulate(time_ + h_, f);
    if (!f.allFinite()) throw NumericalError(step_ + 1, force->name(), "non-finite external force");
  }
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    NodeMatrix p = NodeMatrix::Zero(constraints_[c]->rowCount(), 3);
    constraints_[c]->project(lastGood, p);
    if (!p.allFinite())
      throw NumericalError(step_ + 1, constraints_[c]->name(), "non-finite projection");
  }
  throw NumericalError(step_ + 1, "solver", "non-finite positions after the global solve");
}

void Simulator::run(int steps, Trajectory& trajectory,
                    const std::function<void(const StepStats&)>& progress) {
  if (trajectory.positions.empty()) {
    trajectory.positions.push_back(x_);
    trajectory.velocities.push_back(v_);
    trajectory.moduleNames = timer_->names();
    trajectory.model = compiled_;
  }
  trajectory.positions.reserve(trajectory.positions.size() + steps);
  trajectory.velocities.reserve(trajectory.velocities.size() + steps);
  if (contact_) trajectory.contacts.reserve(trajectory.contacts.size() + steps);
  for (int s = 0; s < steps; ++s) {
    const StepStats& st = step();
    trajectory.positions.push_back(x_);
    trajectory.velocities.push_back(v_);
    trajectory.steps.push_back(st);
    if (contact_) trajectory.contacts.push_back(lastContacts_);
    if (progress) progress(st);
  }
}

}  // namespace weft
