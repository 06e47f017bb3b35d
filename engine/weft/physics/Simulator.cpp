#include <weft/physics/Simulator.h>

#include <weft/collision/ImpactZoneResponse.h>
#include <weft/contact/FrictionalContact.h>
#include <weft/core/Error.h>
#include <weft/physics/AttachmentConstraint.h>
#include <weft/physics/ExternalForce.h>
#include <weft/physics/ModuleTimer.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/StepContext.h>
#include <weft/physics/StepSolver.h>
#include <weft/physics/SystemMatrix.h>
#include <weft/record/ConvergenceReport.h>

#include <algorithm>
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

struct Simulator::Level {
  int halvings = 0;                      // dt / 2^halvings
  std::shared_ptr<const Model> model;    // the scene at this level's dt
  std::unique_ptr<SystemMatrix> system;  // P and its factor
  std::unique_ptr<StepContext> context;  // what the solves share
  std::unique_ptr<StepSolver> solver;
  NodeMatrix start, startVelocity;  // the state the last attempt started from
};

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
  for (const auto& c : constraints_) {
    constraintModule_.push_back(timer_->add(c->name()));
    if (std::string(c->name()) == "handles")
      handles_ = dynamic_cast<AttachmentConstraint*>(c.get());
  }
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

  if (scene_.hasImpactZones()) {
    const auto start = ModuleTimer::Clock::now();
    impactZones_ = std::make_unique<collision::ImpactZoneResponse>(scene_, model_);
    impactZoneModule_ = timer_->add("impact_zones");
    timer_->charge(impactZoneModule_, ModuleTimer::secondsSince(start));
  }

  const int m = model_.nodeCount();
  x_ = model_.rest.vertices;
  v_ = compiled_->initialVelocities();
  warmStart_.setZero(m, 3);
  force_.setZero(m, 3);
  if (contact_) predicted_.setZero(m, 3);
  warmStartStep_ = h_;
  level(0);
}

Simulator::~Simulator() = default;

Simulator::Level& Simulator::level(int halvings) {
  while (static_cast<int>(levels_.size()) <= halvings) {
    const int k = static_cast<int>(levels_.size());
    auto level = std::make_unique<Level>();
    level->halvings = k;
    level->model = k == 0 ? compiled_ : compiled_->withTimeStep(h_ / static_cast<double>(1 << k));
    const double h = level->model->dt();
    timer_->timed(solverModule_, [&] {
      level->system = std::make_unique<SystemMatrix>(model_.mass, constraints_, h);
    });
    level->context = std::make_unique<StepContext>(
        *level->model, x_, constraints_, constraintModule_, *level->system, *timer_, solverModule_,
        contact_.get(), contactSolveModule_);
    level->solver = makeStepSolver(*level->context);
    levels_.push_back(std::move(level));
  }
  return *levels_[static_cast<std::size_t>(halvings)];
}

const std::vector<std::string>& Simulator::moduleNames() const {
  return timer_->names();
}
const std::vector<double>& Simulator::moduleSeconds() const {
  return timer_->seconds();
}
const Eigen::SparseMatrix<double>& Simulator::systemMatrix() const {
  return levels_.front()->system->matrix();
}

namespace {

// A step (or piece) adaptive time stepping keeps (Simulator::step).
bool solved(const StepStats& s) {
  return s.converged && s.depth <= ConvergenceReport::kDepthTolerance;
}

}  // namespace

const StepStats& Simulator::step() {
  timer_->beginStep();
  lastSubsteps_.clear();
  StepStats& total = stepStats_;
  const double t1 = time_ + h_;
  // Adaptive time stepping (SolverSettings::maxHalvings): a step that did not converge, or left
  // a node deeper than ConvergenceReport::kDepthTolerance inside an obstacle's skin (the
  // contact frames are frozen at the step's start, DiffCloth Eq. 9, and a curved or folded
  // obstacle leaves an O(h^2) error), is solved again as two halves, each split further while
  // it fails so, down to dt / 2^maxHalvings; the pieces' states and contacts are kept for the
  // backward pass. With SolverSettings::rememberHalvings, as in a step-size controller, a step
  // starts at the level the last one needed (chooseNextStart): a failed attempt is expensive.
  const int first = std::min(nextStart_, scene_.solver.maxHalvings);
  bool failedFirst = false;
  if (first == 0) {
    total = attempt(level(0), time_);
    failedFirst = !solved(total);
  }
  if (first > 0 || (failedFirst && scene_.solver.maxHalvings > 0)) {
    const int spent = total.pdIterations, sweeps = total.contactSweeps, late = total.lateContacts;
    total = StepStats{};
    total.step = step_ + 1;
    total.time = t1;
    total.converged = true;
    total.substeps = 0;
    if (first == 0) {  // (the failed whole attempt's work counts)
      total.pdIterations = spent;
      total.contactSweeps = sweeps;
      total.lateContacts = late;
    }
    subdivide(1, std::max(first, 1), time_, total, failedFirst);
  } else {
    accept(level(0), total);
  }
  chooseNextStart(first, failedFirst);
  time_ = t1;  // (the pieces' ends add up to it up to rounding)
  ++step_;
  total.moduleSeconds = timer_->stepSeconds();
  return total;
}

void Simulator::chooseNextStart(int first, bool failedFirst) {
  // With SolverSettings::rememberHalvings: one level finer after a failure at the first level;
  // one coarser after kCleanSteps steps in a row solved where they started (the contact set of
  // an impact settles within a few steps; growing after every success would pay for a failed
  // attempt every other step). Without, every step starts whole.
  constexpr int kCleanSteps = 2;
  if (!scene_.solver.rememberHalvings) return;
  if (failedFirst) {
    nextStart_ = std::min(first + 1, scene_.solver.maxHalvings);
    cleanSteps_ = 0;
  } else if (first > 0 && ++cleanSteps_ >= kCleanSteps) {
    nextStart_ = first - 1;
    cleanSteps_ = 0;
  }
}

void Simulator::subdivide(int halvings, int first, double t0, StepStats& total, bool& failedFirst) {
  Level& fine = level(halvings);
  const double h = fine.model->dt();
  for (int half = 0; half < 2; ++half) {
    const double start = t0 + half * h;
    if (halvings < first) {
      subdivide(halvings + 1, first, start, total, failedFirst);
      continue;
    }
    const StepStats s = attempt(fine, start);
    total.pdIterations += s.pdIterations;
    total.contactSweeps += s.contactSweeps;
    total.lateContacts += s.lateContacts;
    if (!solved(s) && halvings == first) failedFirst = true;
    if (!solved(s) && halvings < scene_.solver.maxHalvings) {
      subdivide(halvings + 1, first, start, total, failedFirst);
      continue;
    }
    accept(fine, total);
    Substep piece;
    piece.model = fine.model;
    piece.halvings = halvings;
    piece.time = s.time;
    piece.x0 = fine.start;
    piece.v0 = fine.startVelocity;
    piece.x1 = x_;
    piece.contacts = lastContacts_;
    lastSubsteps_.push_back(std::move(piece));
    ++total.substeps;
    total.halvings = std::max(total.halvings, halvings);
    total.converged = total.converged && s.converged;
    total.residual = std::max(total.residual, s.residual);
    total.depth = std::max(total.depth, s.depth);
    total.takeoff = s.takeoff;
    total.stick = s.stick;
    total.slip = s.slip;
    total.contactSweepChange = s.contactSweepChange;
  }
}

const StepStats& Simulator::attempt(Level& level, double t0) {
  const double h = level.model->dt();
  const double h2 = h * h;
  const double t1 = t0 + h;
  const SolverSettings& solver = scene_.solver;
  StepContext& ctx = *level.context;
  StepSolver& stepSolver = *level.solver;
  StepStats& stats = ctx.stats;
  stats = StepStats{};
  stats.step = step_ + 1;
  stats.time = t1;
  ctx.solveLimit = solver.pdIterations;
  ctx.splittable = level.halvings < solver.maxHalvings;
  level.start = x_;
  level.startVelocity = v_;

  // External forces at the end of the step (implicit Euler, Eqs. 1-2).
  force_.setZero();
  const auto& forces = compiled_->forces();
  for (std::size_t f = 0; f < forces.size(); ++f)
    timer_->timed(forceModule_[f], [&] { forces[f]->accumulate(t1, force_); });
  for (std::size_t c = 0; c < constraints_.size(); ++c)
    timer_->timed(constraintModule_[c], [&] { constraints_[c]->beginStep(t1, x_); });

  timer_->timed(solverModule_, [&] {
    // y = x_n + h v_n + h^2 M^{-1} f_ext (Eq. 3)
    ctx.y = x_ + h * v_ + h2 * (ctx.inverseMass.asDiagonal() * force_);
    ctx.massY = model_.mass.asDiagonal() * ctx.y;
    // Warm start: the displacement the internal forces caused last step (x_n - y_{n-1}) changes
    // slowly, and carries the slow, bending-like modes that PD is slowest to converge. It scales
    // with h^2 (warmStartStep_ is the h it was made with).
    const double scale = (h / warmStartStep_) * (h / warmStartStep_);
    ctx.iterate = ctx.y + scale * warmStart_;
  });

  if (contact_) {
    detectContacts(level, t0, t1);
    stepSolver.solve(ctx);
    // Detection saw the predicted path only (DiffCloth Eq. 9's frames from x_n, v_n); where the
    // path the solve took strays from it, contacts it meets that the set lacks are added and the
    // step is solved again from its result, each pass with a fresh iteration budget.
    // An unconverged attempt that will be split is not worth the passes: it is thrown away.
    for (int pass = 0; pass < kMissedContactPasses && stepSolver.resolvesMissedContacts() &&
                       (stats.converged || !ctx.splittable);
         ++pass) {
      int added = 0;
      timer_->timed(contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_,
                    [&] {
                      ctx.change = ctx.global - x_;
                      added = contact_->addMissedContacts(x_, predicted_, ctx.change);
                    });
      if (added == 0) break;
      stats.lateContacts += added;
      timer_->timed(contactSolveModule_, [&] { stepSolver.prepareContacts(ctx); });
      timer_->timed(solverModule_, [&] { ctx.iterate = ctx.global; });
      ctx.solveLimit = stats.pdIterations + solver.pdIterations;
      stepSolver.solve(ctx);
    }
    timer_->timed(contactSolveModule_, [&] {
      stepSolver.record(ctx, lastContacts_);
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
    stepSolver.solve(ctx);
  }
  // The last global solution is the step's result (one PD iteration past the checked iterate).
  if (!ctx.global.allFinite()) diagnoseNonFinite(x_, t1);
  if (contact_ && contact_->hasObstacles())
    timer_->timed(contactDetectionModule_,
                  [&] { stats.depth = contact_->deepestPenetration(ctx.global); });
  return stats;
}

void Simulator::accept(Level& level, StepStats& total) {
  StepContext& ctx = *level.context;
  const double h = level.model->dt();
  // Impact zones (Liang 2019 Algorithm 1 lines 7-8): the collision response moves the solved
  // positions, and the velocity follows from the positions it leaves.
  if (impactZones_)
    timer_->timed(impactZoneModule_, [&] { impactZones_->apply(x_, ctx.global, total); });
  v_ = (ctx.global - x_) / h;
  x_ = ctx.global;
  warmStart_ = x_ - ctx.y;
  warmStartStep_ = h;
  time_ = ctx.stats.time;
  const double maxSpeed = std::sqrt(v_.rowwise().squaredNorm().maxCoeff());
  if (!(maxSpeed < kBlowUpSpeed))
    throw NumericalError(ctx.stats.step, "solver",
                         "velocity " + std::to_string(maxSpeed) + " m/s: the integration blew up");
}

void Simulator::detectContacts(Level& level, double t0, double t1) {
  // The contact set and frames are found once per step from x_n and the predicted motion (the
  // warm-started first iterate), and stay frozen during the iterations: the explicit J_n(x_n,
  // v_n) of DiffCloth Eq. 9; after the solve, step() adds contacts the path taken violated and
  // the predicted one missed (FrictionalContact::addMissedContacts).
  const int first = contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_;
  timer_->timed(first, [&] {
    contact_->beginStep(t0, t1);
    predicted_ = level.context->iterate - x_;
  });
  if (contact_->hasObstacles())
    timer_->timed(contactDetectionModule_, [&] { contact_->detectObstacles(x_, predicted_); });
  if (contact_->hasSelfCollision())
    timer_->timed(selfCollisionModule_, [&] { contact_->detectSelfCollisions(x_, predicted_); });
  timer_->timed(contactSolveModule_, [&] { level.solver->prepareContacts(*level.context); });
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
  warmStartStep_ = h_;
  nextStart_ = 0;
  cleanSteps_ = 0;
}

void Simulator::driveHandle(int handle, const Vec3& offset) {
  const std::vector<HandleGroup>& groups = compiled_->handles();
  if (handle < 0 || handle >= static_cast<int>(groups.size()) || !handles_)
    throw std::out_of_range("Simulator::driveHandle: the scene has no handle " +
                            std::to_string(handle));
  int row = 0;  // the handles family's rows take the groups in order
  for (int g = 0; g < handle; ++g) row += static_cast<int>(groups[g].nodes.size());
  for (std::size_t k = 0; k < groups[handle].nodes.size(); ++k)
    handles_->drive(row + static_cast<int>(k), offset);
}

void Simulator::diagnoseNonFinite(const NodeMatrix& lastGood, double t1) const {
  NodeMatrix f = NodeMatrix::Zero(lastGood.rows(), 3);
  for (const auto& force : compiled_->forces()) {
    force->accumulate(t1, f);
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
    trajectory.substeps.push_back(lastSubsteps_);
    if (progress) progress(st);
  }
}

}  // namespace weft
