#include <weft/physics/Simulator.h>

#include <weft/core/Error.h>
#include <weft/physics/AttachmentConstraint.h>
#include <weft/physics/BendingConstraint.h>
#include <weft/physics/GravityForce.h>
#include <weft/physics/NodalForces.h>
#include <weft/physics/StretchConstraint.h>
#include <weft/physics/WindForce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <utility>

namespace weft {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The Newton contact solve (Simulator::solveContactNewton).
// K+ is refactorised when a GMRES solve needed more than this many iterations (the iterate and
// the branches moved far from where it was factorised).
constexpr int kRefactorIterations = 20;
// GMRES iterations a step's first linear solve may take with P before K+ is factorised.
constexpr int kPIterations = 5;
// Where one factorisation of K+ costs more than this many iterations with P (keepStiffnessFactor_),
// a step starts from the previous step's factor of K+ instead of P.
constexpr double kKeepFactorAbovePIterations = 30.0;
// Measured seconds per flop of CHOLMOD's supernodal factorisation of K+ over those of an
// iteration with P (reference BLAS, one thread; 48x48 Slope: 200 ms per factorisation, 2.5 ms
// per iteration, against a flop ratio of 116).
constexpr double kFactorTimePerFlopRatio = 0.7;
constexpr int kGmresRestart = 100;
// Backtracking stops below this step length; then a full Newton step is still taken if its
// residual stays below kRelaxedGrowth times the best one so far (a non-monotone step, at most
// kRelaxedSteps in a row: after a branch switch the next linearisation corrects the full step,
// while the backtracking would creep along the old branch). The step's result is the best
// iterate visited.
constexpr double kMinStep = 1e-3;
constexpr double kRelaxedGrowth = 100.0;
constexpr int kRelaxedSteps = 3;
// Times a step is solved again with contacts its solved path violated and detection missed
// (step()).
constexpr int kMissedContactPasses = 2;

// Diagnostics: WEFT_CONTACT_TRACE=a-b (or =a) prints each Newton contact iteration of steps a..b
// to stderr (residual, GMRES iterations, step length, branch changes).
// Read once, by a static initialiser, which is thread-safe: simulators may run on several
// threads at once (`weft bench applications --jobs`, the editor's workers).
bool traceContactStep(int step) {
  static const std::pair<int, int> range = [] {
    int first = 0, last = -1;
    if (const char* e = std::getenv("WEFT_CONTACT_TRACE"))
      if (std::sscanf(e, "%d-%d", &first, &last) == 1) last = first;
    return std::pair<int, int>(first, last);
  }();
  return step >= range.first && step <= range.second;
}

// A speed no cloth reaches unless the integration has blown up.
constexpr double kBlowUpSpeed = 1e5;  // m/s

}  // namespace

Simulator::Simulator(const Scene& scene)
    : scene_(scene), model_(buildClothModel(scene)), h_(scene.time.dt) {
  solverModule_ = addModule("solver");
  // Constraint modules: only those with at least one instance.
  auto addConstraint = [this](std::unique_ptr<ProjectiveConstraint> c) {
    if (c->rowCount() == 0) return;
    constraintModule_.push_back(addModule(c->name()));
    constraints_.push_back(std::move(c));
  };
  addConstraint(std::make_unique<StretchConstraint>(makeStretchConstraint(scene, model_)));
  addConstraint(std::make_unique<BendingConstraint>(makeBendingConstraint(scene, model_)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, model_, false)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, model_, true)));

  // Force modules: only the effects the scene names.
  auto addForce = [this](std::unique_ptr<ExternalForce> f) {
    forceModule_.push_back(addModule(f->name()));
    forces_.push_back(std::move(f));
  };
  if (scene.gravity) addForce(std::make_unique<GravityForce>(*scene.gravity, model_.mass));
  if (scene.wind) addForce(std::make_unique<WindForce>(*scene.wind, model_.lumpedArea));
  bool anyNodalForce = false;
  NodeMatrix nodal = NodeMatrix::Zero(model_.nodeCount(), 3);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (const PointForce& pf : scene.cloths[c].forces)
      for (int v : pf.vertices) {
        nodal.row(model_.vertexOffset[c] + v) += pf.force.transpose();
        anyNodalForce = true;
      }
  if (anyNodalForce) addForce(std::make_unique<NodalForces>(std::move(nodal)));

  // Contact modules: only for scenes with obstacles or self-collision.
  if (!scene.obstacles.empty() || scene.hasSelfCollision()) {
    const auto start = Clock::now();
    contact_ = std::make_unique<FrictionalContact>(scene, model_);
    if (contact_->hasObstacles()) contactDetectionModule_ = addModule("contact_detection");
    if (contact_->hasSelfCollision()) selfCollisionModule_ = addModule("self_collision");
    contactSolveModule_ = addModule("contact_solve");
    // Building the shapes (mesh BVHs) and the self-collision tables counts as detection.
    moduleSeconds_[contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_] +=
        secondsSince(start);
  }

  const int m = model_.nodeCount();
  inverseMass_ = model_.mass.cwiseInverse();
  massRoot_ = model_.mass.cwiseSqrt();
  x_ = model_.rest.vertices;
  v_.resize(m, 3);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (int i = model_.vertexOffset[c]; i < model_.vertexOffset[c + 1]; ++i)
      v_.row(i) = scene.cloths[c].initialVelocity.transpose();
  for (auto* buf :
       {&warmStart_, &force_, &y_, &massY_, &iterate_, &global_, &accelerated_, &change_, &rhs_,
        &residualVector_, &direction_, &cgResidual_, &cgPreconditioned_, &cgSearch_, &cgProduct_})
    buf->setZero(m, 3);
  for (const auto& c : constraints_) {
    projections_.emplace_back(NodeMatrix::Zero(c->rowCount(), 3));
    derivativeRows_.emplace_back(NodeMatrix::Zero(c->hasDerivative() ? c->rowCount() : 0, 3));
  }
  if (contact_)
    for (auto* buf :
         {&freeMomentum_, &plainIterate_, &fullResidual_, &lawInput_, &pinnedPart_, &predicted_})
      buf->setZero(m, 3);
  totalMass_ = model_.mass.sum();
  if (scene.solver.acceleration == Acceleration::Anderson)
    anderson_.reset(3 * m, scene.solver.andersonWindow);

  const auto start = Clock::now();
  assembleAndFactorize();
  moduleSeconds_[solverModule_] += secondsSince(start);
  // From operation counts, not timings, so that runs repeat exactly.
  keepStiffnessFactor_ = kFactorTimePerFlopRatio * cholesky_.blockFactorFlopRatio(
                                                       static_cast<double>(system_.nonZeros())) >
                         kKeepFactorAbovePIterations;
}

Simulator::~Simulator() = default;

int Simulator::addModule(const std::string& name) {
  moduleNames_.push_back(name);
  moduleSeconds_.push_back(0.0);
  return static_cast<int>(moduleNames_.size()) - 1;
}

void Simulator::assembleAndFactorize() {
  system_ = assembleSystemMatrix(model_.mass, constraints_, h_);
  systemRows_ = system_;
  // The Newton contact solve's law mass (solveContactNewton): the geometric mean of the lumped
  // mass and P's diagonal.
  lawMass_ = (model_.mass.array() * system_.diagonal().array()).sqrt().matrix();
  if (!cholesky_.factorize(system_))
    throw NumericalError(0, "solver", "system matrix P is not positive definite");
}

double Simulator::localStep(const NodeMatrix& x, bool energy) {
  // Inertia term of g (DiffCloth Eq. 3): |x - y|^2_M / (2 h^2).
  double total = 0.0;
  if (energy) {
    for (int c = 0; c < 3; ++c) total += model_.mass.dot((x.col(c) - y_.col(c)).cwiseAbs2());
    total *= 0.5 / (h_ * h_);
  }
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    // A family whose projections are all zero only needs its energy (for the safeguard).
    if (constraints_[c]->projectsToZero() && !energy) continue;
    const auto start = Clock::now();
    const double e = constraints_[c]->projectsToZero()
                         ? constraints_[c]->energy(x)
                         : constraints_[c]->project(x, projections_[c]);
    if (energy) total += e;
    const double s = secondsSince(start);
    moduleSeconds_[constraintModule_[c]] += s;
    stats_.moduleSeconds[constraintModule_[c]] += s;
  }
  return total;
}

template <class Fn>
void Simulator::timed(int module, Fn&& fn) {
  const auto start = Clock::now();
  fn();
  const double s = secondsSince(start);
  moduleSeconds_[module] += s;
  stats_.moduleSeconds[module] += s;
}

void Simulator::globalStep() {
  // Global step (DiffCloth Eq. 7): P x = M y + h^2 sum_i w_i A_i^T p_i, with the projections of
  // the last local step.
  timed(solverModule_, [&] {
    rhs_ = massY_;
    for (std::size_t c = 0; c < constraints_.size(); ++c)
      if (!constraints_[c]->projectsToZero())
        constraints_[c]->gather(projections_[c], h_ * h_, rhs_);
    if (activeContacts_)
      activeContacts_->addFriction(iterate_, h_, rhs_);  // slip friction as an impulse
    global_ = rhs_;
    cholesky_.solveInPlace(global_);
    change_ = global_ - iterate_;
  });
  ++stats_.pdIterations;
}

double Simulator::residualOf(const NodeMatrix& systemTimesChange) const {
  // P (x_global - x_k) = -h^2 grad g(x_k): the imbalance of Eq. 3 at the iterate, as a
  // mass-weighted RMS acceleration (m/s^2).
  const double sum = (systemTimesChange.rowwise().squaredNorm().transpose().array() *
                      inverseMass_.transpose().array())
                         .sum();
  return std::sqrt(sum / totalMass_) / (h_ * h_);
}

void Simulator::multiplySystem(const NodeMatrix& in, NodeMatrix& out) const {
  const int m = static_cast<int>(systemRows_.rows());
  const int* outer = systemRows_.outerIndexPtr();
  const int* inner = systemRows_.innerIndexPtr();
  const double* value = systemRows_.valuePtr();
  const double *ix = in.col(0).data(), *iy = in.col(1).data(), *iz = in.col(2).data();
  double *ox = out.col(0).data(), *oy = out.col(1).data(), *oz = out.col(2).data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < m; ++i) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int j = inner[k];
      sx += value[k] * ix[j], sy += value[k] * iy[j], sz += value[k] * iz[j];
    }
    ox[i] = sx, oy[i] = sy, oz[i] = sz;
  }
}

void Simulator::multiplyNewtonMatrix(const NodeMatrix& in, NodeMatrix& out) {
  // K = P - Delta P (Sec. 4.1) with Delta P = h^2 sum_i w_i A_i^T D_i A_i, D_i the projection
  // derivative: K = h^2 x (Hessian of g).
  multiplySystem(in, out);
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    if (!constraints_[c]->hasDerivative()) continue;
    timed(constraintModule_[c], [&] {
      constraints_[c]->applyDerivative(in, derivativeRows_[c]);
      constraints_[c]->gather(derivativeRows_[c], -h_ * h_, out);
    });
  }
  if (activeContacts_)
    timed(contactSolveModule_, [&] { activeContacts_->addFrictionHessian(in, out); });
}

bool Simulator::checkConvergence() {
  // P (x_global - x_k): the imbalance of the step's equations at the iterate (residualOf).
  timed(solverModule_, [&] {
    multiplySystem(change_, residualVector_);
    if (activeContacts_) {
      // With contact constraints only the imbalance in the free directions must vanish; the rest
      // is the contact impulse (kept whole for the multipliers).
      fullResidual_ = residualVector_;
      activeContacts_->projectDirection(residualVector_);
    }
    stats_.residual = residualOf(residualVector_);
  });
  stats_.converged = stats_.residual < scene_.solver.pdTolerance;
  return stats_.converged;
}

void Simulator::solveProjectiveDynamics() {
  const SolverSettings& solver = scene_.solver;
  double previousEnergy = std::numeric_limits<double>::infinity();
  bool accelerated = false;
  while (stats_.pdIterations < solver.pdIterations) {
    double energy = localStep(iterate_);
    // Safeguard (Peng et al. 2018): an accelerated iterate that raised the energy is replaced by
    // the plain PD iterate, which never does (it minimises the surrogate of Eq. 6). The slack
    // absorbs round-off once the energy has converged to its last digits.
    if (accelerated && !(energy <= previousEnergy + 1e-13 * std::abs(previousEnergy))) {
      iterate_ = global_;
      anderson_.restart();
      energy = localStep(iterate_);
    }
    previousEnergy = energy;
    globalStep();
    if (checkConvergence()) return;
    timed(solverModule_, [&] {
      if (solver.acceleration == Acceleration::Anderson) {
        anderson_.next(iterate_.data(), global_.data(), accelerated_.data());
        iterate_.swap(accelerated_);
        accelerated = true;
      } else {
        iterate_ = global_;
      }
    });
  }
}

bool Simulator::iterateNewton() {
  // Newton on g (Eq. 3) with conjugate gradients preconditioned by the prefactorised P. The
  // Hessian is h^-2 (P - Delta P) with the exact projection derivative (the same Delta P the
  // adjoint uses, Sec. 4.1). The first preconditioned residual is exactly the PD step
  // x_global - x, so one CG iteration reproduces PD; further ones add the curvature PD leaves out
  // (the soft out-of-plane modes where P overestimates the stiffness), and convergence becomes
  // quadratic. Where the Hessian is indefinite (compressed triangles), CG stops at the negative
  // curvature, and a step that does not decrease g falls back to the PD step, which always does.
  //
  // With contact constraints (activeContacts_), the same iteration runs in the subspace
  // {C d = 0} (projected PCG: residual, preconditioned residual and products projected), on g
  // plus the potential of the lagged slip friction; iterates stay feasible. The PD step is then
  // not a fallback (it leaves the subspace): a step the line search rejects ends the iteration.
  const SolverSettings& solver = scene_.solver;
  const double h2 = h_ * h_;
  ActiveContactSet* const contacts = activeContacts_;
  auto energyAt = [&](const NodeMatrix& x) {
    double e = localStep(x);
    if (contacts) e += contacts->frictionPotential(x);
    return e;
  };
  double energy = energyAt(iterate_);
  double forcing = 0.5, previousResidual = 0.0;
  auto dot = [](const NodeMatrix& a, const NodeMatrix& b) { return (a.array() * b.array()).sum(); };
  const double velocityTolerance = solver.pdTolerance * h_;
  while (stats_.pdIterations < solver.pdIterations) {
    globalStep();
    const bool small =
        checkConvergence();  // also leaves r0 = b - P x = P (x_global - x) in residualVector_
    if (contacts) {
      // Branch update at every iterate (a primal-dual active-set strategy): the branches and the
      // elastic solve converge together instead of one Newton solve per active set.
      // The lagged slip friction is re-aimed once the elastic part has converged.
      int changed = 0;
      timed(contactSolveModule_, [&] {
        changed = contacts->update(iterate_, fullResidual_, velocityTolerance, small);
        if (changed > 0) contacts->projectPositions(iterate_);
      });
      ++stats_.contactSweeps;
      if (changed > 0 || contacts->lastChange() > velocityTolerance) {
        stats_.converged = false;
        energy = energyAt(iterate_);
        previousResidual = 0.0;
        forcing = 0.5;
        continue;
      }
    }
    if (small) {
      // A step whose contacts cycle ends here too; it counts as not converged.
      if (contacts && contacts->blocked() > 0) stats_.converged = false;
      return stats_.converged;
    }
    for (std::size_t c = 0; c < constraints_.size(); ++c)
      if (constraints_[c]->hasDerivative())
        timed(constraintModule_[c], [&] { constraints_[c]->prepareDerivative(iterate_, false); });
    if (contacts) timed(contactSolveModule_, [&] { contacts->prepareFrictionHessian(iterate_); });

    // PCG on K d = r0, preconditioner P^{-1}; z0 = P^{-1} r0 = change_ (no extra solve).
    if (contacts) {
      // z0 = Pi P^{-1} Pi r0, one more solve; change_ becomes the fallback direction.
      timed(solverModule_, [&] {
        change_ = residualVector_;
        cholesky_.solveInPlace(change_);
        contacts->projectDirection(change_);
      });
      ++stats_.pdIterations;
    }
    direction_.setZero();
    cgResidual_ = residualVector_;
    cgPreconditioned_ = change_;
    cgSearch_ = change_;
    double rz = dot(cgResidual_, cgPreconditioned_);
    const double rz0 = rz;
    // Inexact Newton: the CG tolerance follows the residual's decrease (Eisenstat-Walker choice 2),
    // loose while far from the solution, tight once convergence is quadratic.
    if (previousResidual > 0.0) {
      const double ratio = stats_.residual / previousResidual;
      const double safeguard = 0.9 * forcing * forcing;
      forcing = std::max(0.9 * ratio * ratio, safeguard > 0.1 ? safeguard : 0.0);
      forcing = std::min(0.5, std::max(forcing, 1e-6));
    }
    // No need to reduce the linear residual much below what the tolerance asks of the nonlinear
    // one: the linear model predicts a residual of about forcing * residual after the step.
    forcing = std::min(0.5, std::max(forcing, 0.25 * solver.pdTolerance / stats_.residual));
    previousResidual = stats_.residual;
    while (true) {
      multiplyNewtonMatrix(cgSearch_, cgProduct_);
      if (contacts) timed(solverModule_, [&] { contacts->projectDirection(cgProduct_); });
      double curvature = 0.0, alpha = 0.0;
      timed(solverModule_, [&] {
        curvature = dot(cgSearch_, cgProduct_);
        if (curvature > 0.0) {
          alpha = rz / curvature;
          direction_ += alpha * cgSearch_;
          cgResidual_ -= alpha * cgProduct_;
        }
      });
      if (!(curvature > 0.0) || stats_.pdIterations >= solver.pdIterations) break;
      timed(solverModule_, [&] {
        cgPreconditioned_ = cgResidual_;
        cholesky_.solveInPlace(cgPreconditioned_);
        if (contacts) contacts->projectDirection(cgPreconditioned_);
      });
      ++stats_.pdIterations;
      const double rzNew = dot(cgResidual_, cgPreconditioned_);
      if (rzNew <= forcing * forcing * rz0) break;
      timed(solverModule_, [&] { cgSearch_ = cgPreconditioned_ + (rzNew / rz) * cgSearch_; });
      rz = rzNew;
    }
    if (direction_.isZero(0.0)) direction_ = change_;

    // Backtracking line search on g (Armijo); the PD step is the fallback, since it always
    // decreases g. grad g = -r0 / h^2.
    const double slope = -dot(residualVector_, direction_) / h2;
    double step = 1.0;
    bool accepted = false;
    for (int tries = 0; tries < 8 && !accepted; ++tries, step *= 0.5) {
      accelerated_ = iterate_ + step * direction_;
      const double trial = energyAt(accelerated_);
      if (trial <= energy + 1e-4 * step * slope + 1e-13 * std::abs(energy)) {
        iterate_.swap(accelerated_);
        energy = trial;
        accepted = true;
      }
    }
    if (!accepted) {
      if (contacts) return false;
      iterate_ = global_;
      energy = localStep(iterate_);
    }
  }
  return false;
}

void Simulator::solveNewtonWithContact() {
  // Active-set Newton (ActiveContactSet.h). Convergence test of the contact solve: no branch
  // change and no friction impulse change above pd_tolerance * h as a velocity (m/s), the
  // velocity error the elastic tolerance allows over one step, together with the elastic
  // residual below pd_tolerance.
  ActiveContactSet& set = contact_->activeSet();
  timed(contactSolveModule_, [&] {
    set.guessBranches(iterate_);
    set.projectPositions(iterate_);
  });
  activeContacts_ = &set;
  iterateNewton();
  activeContacts_ = nullptr;
  timed(contactSolveModule_, [&] { set.refreshVelocities(iterate_); });
  stats_.contactSweepChange = set.lastChange();
  // The feasible iterate is the step's result (a PD solve past it would leave the constraints).
  global_ = iterate_;
}

void Simulator::detectContacts(double t0, double t1) {
  // The contact set and frames are found once per step from x_n and the predicted motion (the
  // warm-started first iterate), and stay frozen during the iterations: the explicit J_n(x_n,
  // v_n) of DiffCloth Eq. 9; after the solve, step() adds contacts the path taken violated and
  // the predicted one missed (FrictionalContact::addMissedContacts).
  const int first = contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_;
  timed(first, [&] {
    contact_->beginStep(t0, t1);
    predicted_ = iterate_ - x_;
  });
  if (contact_->hasObstacles())
    timed(contactDetectionModule_, [&] { contact_->detectObstacles(x_, predicted_); });
  if (contact_->hasSelfCollision())
    timed(selfCollisionModule_, [&] { contact_->detectSelfCollisions(x_, predicted_); });
  timed(contactSolveModule_, [&] {
    contactLawMass_ = scene_.solver.contact == ContactMethod::Newton ? &lawMass_ : nullptr;
    if (scene_.solver.contact == ContactMethod::ActiveSet)
      contact_->prepareActiveSet(x_, scene_.solver.pdTolerance * h_);
    else
      contact_->prepareSolve(contactLawMass_);
  });
}

void Simulator::assembleContactRhs(const NodeMatrix& x, NodeMatrix& systemTimesX) {
  // rhs_ = b(x) + h r(f(x)) (DiffCloth Eqs. 10-12; notes Sec. 2.1) from the last local step's
  // projections, and P x. In positions, P v = b_hat + r is P x = b + h r.
  timed(solverModule_, [&] {
    rhs_ = massY_;
    for (std::size_t c = 0; c < constraints_.size(); ++c)
      if (!constraints_[c]->projectsToZero())
        constraints_[c]->gather(projections_[c], h_ * h_, rhs_);
    multiplySystem(x, systemTimesX);
  });
  if (contact_->empty()) return;
  timed(solverModule_, [&] {
    // Free momentum f = b_hat - (P - M) v^k = M (x^k - x_n)/h + (b - P x^k)/h, which equals
    // M v_n + h (f_ext + f_int(x^k)): the momentum each node would have without contact,
    // predicted with the diagonal M as in Eq. 12. The Newton solve uses its law mass m~ in place
    // of M (ContactSolver::setContacts): the same solution, other iterates.
    const Eigen::VectorXd& lawMass = contactLawMass_ ? *contactLawMass_ : model_.mass;
    freeMomentum_ = (rhs_ - systemTimesX + lawMass.asDiagonal() * (x - x_)) / h_;
  });
  timed(contactSolveModule_, [&] {
    // Sweeps stop when no impulse changes by more than a tenth of what the PD tolerance allows
    // over one step (as a velocity); see ContactSolver.h.
    stats_.contactSweeps += contact_->solve(freeMomentum_, 0.1 * scene_.solver.pdTolerance * h_);
    stats_.contactSweepChange = contact_->lastSweepChange();
    contact_->addImpulses(h_, rhs_);
  });
}

void Simulator::contactGlobalStep() {
  // Velocity-form global step with contact (DiffCloth Eqs. 10-12): x = P^-1 (b + h r).
  assembleContactRhs(iterate_, fullResidual_);  // (P x in fullResidual_, scratch on this path)
  timed(solverModule_, [&] {
    global_ = rhs_;
    cholesky_.solveInPlace(global_);
    change_ = global_ - iterate_;
  });
  ++stats_.pdIterations;
}

void Simulator::solveWithPerNodeContact() {
  // A step whose contact set is empty has an energy, g (Eq. 3): with solver.method "newton" it
  // is solved as in a scene without obstacles, Newton with an Armijo line search on g and the
  // PD step as the fallback, which always decreases g. Neither contact solve has that
  // globalisation: the semismooth one backtracks on the residual norm, which a direction of the
  // indefinite K of compressed, buckling cloth need not decrease (the Sock's tube hanging from
  // its cuff: steps starting at a residual of 8.6e2 m/s^2 stalled at 3 to 30 with either
  // contact solve; this way every such step converges, in about 80 solves with P).
  if (contact_->perNodeSolver().empty() && scene_.solver.method == SolverMethod::Newton) {
    solveNewton();
    return;
  }
  if (scene_.solver.contact == ContactMethod::Newton) {
    solveContactNewton();
    if (!stats_.converged && std::isfinite(stats_.residual) && stats_.pdIterations < solveLimit_)
      finishWithPerNodeIterations();
    return;
  }
  if (scene_.solver.acceleration == Acceleration::Anderson) anderson_.restart();
  solveWithContact();
}

void Simulator::finishWithPerNodeIterations() {
  // The semismooth Newton solve stalled (its line search on the residual norm found no
  // decrease): the PD contact iteration continues from its result with the rest of the budget.
  // Where Newton stalls the residual can sit on a few nodes away from any contact (the Sock at
  // step 45: four nodes of one hinge below the toe held 99.9 % of it), where a stretch or
  // bending projection's derivative is discontinuous (a collapsed or flipped element) and the
  // residual norm is not smooth; the PD iteration needs no derivative there. It runs with the
  // lumped mass in the law (the PD iteration is not a contraction with Newton's m~, see
  // solveContactNewton's end), which does not change the solution, and the free momentum it
  // hands the law is then the lumped mass's too: built with m~, the law saw the velocity
  // (m~ / m) v (about 55 v on the Sock), which leaves a stick or slip decision unchanged but
  // closes a gap at m / m~ of its rate, so the continuation converged to other equations. The
  // better of the two results is the step's.
  newtonResult_ = iterate_;
  const double newtonResidual = stats_.residual;
  const Eigen::VectorXd* newtonLawMass = contactLawMass_;
  contactLawMass_ = nullptr;
  timed(contactSolveModule_, [&] { contact_->prepareSolve(nullptr); });
  if (scene_.solver.acceleration == Acceleration::Anderson) anderson_.restart();
  solveWithContact();
  contactLawMass_ = newtonLawMass;
  const bool better = stats_.converged || stats_.residual < newtonResidual;
  // Kept, the PD iteration's result comes with its contact state, the impulses and branches its
  // last global solve used: that is what the step records (contact_forces.npy, the backward
  // pass). Resetting the solver to the law mass here had cleared them (setContacts starts every
  // contact at take-off with no impulse): 7 of the Sock's 400 steps, pressed on the foot, were
  // recorded free of contact.
  if (!better) {
    // Back to Newton's iterate, with the contact impulses (to be recorded) evaluated there.
    timed(contactSolveModule_, [&] { contact_->prepareSolve(contactLawMass_); });
    iterate_ = newtonResult_;
    stats_.residual = contactResidual(iterate_, fullResidual_);
    stats_.converged = stats_.residual < scene_.solver.pdTolerance;
    timed(solverModule_, [&] { global_ = iterate_; });
  }
  // (Otherwise the PD iteration's last global solution is the step's result, as on its own.)
}

void Simulator::solveWithContact() {
  // PD iterations with the contact solve in each global step (Ly et al. 2020, DiffCloth Eq. 12).
  // Convergence test: the same mass-weighted RMS imbalance as without contact,
  // |P (x^{k+1} - x^k)| / h^2 = |b(x^k) + h r(x^k) - P x^k| / h^2: the residual of the
  // implicit-Euler equations with the contact force at the iterate. It vanishes only when the
  // iterate and the contact impulses both stop changing, i.e. at a solution of Eq. 9.
  //
  // Anderson acceleration (solver.acceleration = "anderson") mixes the last iterates of the
  // fixed-point map x -> G(x) (one such global step). The energy safeguard of the no-contact
  // solver does not apply (friction dissipates, the law is non-smooth), so the safeguard is on
  // the residual: an accelerated iterate whose residual exceeds the previous iterate's is
  // replaced by the plain image of that previous iterate, and the history restarts.
  const SolverSettings& solver = scene_.solver;
  const bool anderson = solver.acceleration == Acceleration::Anderson;
  double previousResidual = std::numeric_limits<double>::infinity();
  bool accelerated = false;
  while (stats_.pdIterations < solveLimit_) {
    localStep(iterate_);
    contactGlobalStep();
    if (checkConvergence()) return;
    if (!anderson) {
      timed(solverModule_, [&] { iterate_ = global_; });
      continue;
    }
    if (accelerated && !(stats_.residual <= previousResidual)) {
      timed(solverModule_, [&] {
        iterate_ = plainIterate_;
        anderson_.restart();
      });
      accelerated = false;
      continue;
    }
    previousResidual = stats_.residual;
    timed(solverModule_, [&] {
      plainIterate_ = global_;
      anderson_.next(iterate_.data(), global_.data(), accelerated_.data());
      iterate_.swap(accelerated_);
    });
    accelerated = true;
  }
}

double Simulator::contactResidual(const NodeMatrix& x, NodeMatrix& residual) {
  localStep(x, false);  // (the Newton solve's test is the residual, not the energy)
  assembleContactRhs(x, residual);
  double measure = 0.0;
  timed(solverModule_, [&] {
    residual -= rhs_;
    measure = residualOf(residual);
  });
  return measure;
}

bool Simulator::factorizeStiffness() {
  // K+ = P - Delta P+ at iterate_ (the derivatives must have been prepared `definite`),
  // assembled from the constraints' element blocks and factorised by CHOLMOD (symbolic analysis
  // kept). (The active-set solve's friction Hessian is not part of it: that solve never gets here.)
  bool ok = false;
  timed(solverModule_, [&] {
    if (!stiffnessAssembly_) {
      stiffnessAssembly_ = std::make_unique<HessianAssembly>(system_);
      stiffnessCholesky_.orderByNodes(system_);
    }
    stiffnessAssembly_->assemble(constraints_, -h_ * h_, stiffness_);
    ok = stiffnessCholesky_.factorize(stiffness_);
  });
  stiffnessFactored_ = ok;
  return ok;
}

void Simulator::preconditionContact(const NodeMatrix& scaled, NodeMatrix& z) {
  // Right preconditioner B of the Newton contact solve. The velocities the branches prescribe
  // (stick: all of u, slip: u_N) have rows m~ in J, so B inverts them exactly per node; the rest
  // is solved with K+ (or P when K+ could not be factorised) restricted to the free directions.
  ContactSolver& contacts = contact_->perNodeSolver();
  const int m = model_.nodeCount();
  timed(solverModule_, [&] {
    z.resize(m, 3);
    lawInput_ = massRoot_.asDiagonal() * scaled;  // (a free buffer here)
    const NodeMatrix& r = lawInput_;
    pinnedPart_.setZero(m, 3);
    contacts.pinnedVelocity(r, pinnedPart_);
    if (!stiffnessFactored_) {
      multiplySystem(pinnedPart_, z);
      z = r - z;
      contacts.removePinned(z);
      cholesky_.solveInPlace(z);
    } else {
      // A NodeMatrix's storage is the flat vector K+ acts on (HessianAssembly's index).
      const Eigen::Index n = 3 * static_cast<Eigen::Index>(m);
      coupling_.resize(m, 3);
      Eigen::Map<Eigen::VectorXd>(coupling_.data(), n).noalias() =
          stiffness_ * Eigen::Map<const Eigen::VectorXd>(pinnedPart_.data(), n);
      z = r - coupling_;
      contacts.removePinned(z);
      stiffnessCholesky_.solveInPlace(z.data(), 1);
    }
    contacts.removePinned(z);
    z += pinnedPart_;
  });
  ++stats_.pdIterations;
}

void Simulator::traceResidualNodes(const NodeMatrix& residual) const {
  // Where the step's residual sits (WEFT_CONTACT_TRACE): the nodes holding the largest shares of
  // the squared, mass-weighted residual (residualOf), with their positions and contact branches.
  // On the Sock, a stalled step's residual sat on the four nodes of one bending hinge
  // (scripts/trace-stall-hinges.py names the hinge).
  constexpr int kShown = 8;
  const Eigen::VectorXd weighted = residual.rowwise().squaredNorm().cwiseProduct(inverseMass_);
  const Eigen::VectorXd share = weighted / std::max(1e-300, weighted.sum());
  std::vector<int> order(static_cast<std::size_t>(share.size()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const auto shown = order.begin() + std::min<std::ptrdiff_t>(kShown, share.size());
  std::partial_sort(order.begin(), shown, order.end(),
                    [&](int a, int b) { return share[a] > share[b]; });
  for (auto it = order.begin(); it != shown; ++it)
    std::fprintf(stderr, "  residual at node %d: share %.3f, x (%.4f, %.4f, %.4f), contact %s\n",
                 *it, share[*it], iterate_(*it, 0), iterate_(*it, 1), iterate_(*it, 2),
                 branchName(contact_->perNodeSolver().branchOfNode(*it)));
}

void Simulator::solveContactNewton() {
  // Semismooth Newton on G(x) = P x - b(x) - h r(f(x)) = 0, the fixed point of the "pd" contact
  // iteration x <- P^-1 (b(x) + h r(f(x))) (DiffCloth Eqs. 10-12): the same per-node law (Eq. 8),
  // so the same solution, and the same convergence test (the mass-weighted RMS of G,
  // residualOf). Two choices differ from the PD iteration, neither changes the solution:
  //  - The law is solved with the mass m~_i = sqrt(m_i P_ii) instead of the lumped m_i
  //    (ContactSolver::setContacts; the augmentation parameter of Alart and Curnier's
  //    formulation). The law decides a contact's branch from its free velocity
  //    w = v + (b - P x) / (h m~): with m~ = m the elastic imbalance of an unconverged iterate is
  //    amplified by P_ii / m_i (about 535 at 24^2 quads on the Sphere scene) and the branches of
  //    rim nodes flip from one iterate to the next; with m~ = P_ii the decisions follow the
  //    iterate's velocity, which lags when a resting cloth starts to slide (Slope: 83 of 100
  //    steps converged against 100). The geometric mean converged all of Slope's steps and as
  //    many of the Sphere's as P_ii (measured over 100 steps each).
  //  - Its Jacobian, with K = P - Delta P (Sec. 4.1) and R' = dr/df from each contact's branch
  //    (ContactLawJacobian.h), J = K + R' (K - M~) (the transpose of the backward pass's
  //    operator, Eq. 29, with M~ for M), is not symmetric, so J d = -G is solved by GMRES (on
  //    M^-1/2 J d = -M^-1/2 G, so that it minimises the convergence test's norm), right-
  //    preconditioned by preconditionContact. P is a poor preconditioner here: P^-1 K has one
  //    eigenvalue per node between m/P_ii and about 0.05 (measured at step 20 of the Sphere
  //    scene without self-collision: 613 of 1875 eigenvalues in [1.4e-3, 0.045], their vectors
  //    97-100 % along the cloth normal), the out-of-plane modes PD's quadratic stretch energy
  //    makes as stiff as in-plane stretching, and GMRES needed about 25 iterations per decade
  //    of residual. A factor of the clamped Hessian K+ brings that to a few. Each step starts
  //    with P (where contacts pin the normal motion, as on Slope, it needs 1-4 iterations); once
  //    a solve takes more than kPIterations, K+ is factorised at the current iterate, the solve
  //    continues from where it was, and K+ is refactorised whenever a later solve needs more than
  //    kRefactorIterations.
  // The step is damped by backtracking on the residual norm; where that fails (the direction
  // crosses a branch switch), a full step is still taken if it does not raise the residual more
  // than kRelaxedGrowth-fold over the best (non-monotone), and the step's result is the best
  // iterate visited.
  ContactSolver& contacts = contact_->perNodeSolver();
  const SolverSettings& solver = scene_.solver;
  const bool trace = traceContactStep(step_ + 1);
  NodeMatrix& residual = cgResidual_;  // G at iterate_
  NodeMatrix& trialResidual = cgProduct_;
  NodeMatrix& step = direction_;
  NodeMatrix& rhs = cgSearch_;
  NodeMatrix& best = plainIterate_;
  const Eigen::VectorXd& lawMass = contactLawMass_ ? *contactLawMass_ : model_.mass;
  auto applyJacobian = [&](const NodeMatrix& in, NodeMatrix& out) {
    multiplyNewtonMatrix(in, out);
    timed(contactSolveModule_, [&] {
      lawInput_ = out - lawMass.asDiagonal() * in;
      contacts.addLawJacobian(lawInput_, out);
      out = massRoot_.cwiseInverse().asDiagonal() * out;
    });
  };
  auto precondition = [&](const NodeMatrix& scaled, NodeMatrix& z) {
    preconditionContact(scaled, z);
  };
  auto prepareDerivatives = [&](bool definite) {
    for (std::size_t c = 0; c < constraints_.size(); ++c)
      if (constraints_[c]->hasDerivative())
        timed(constraintModule_[c],
              [&] { constraints_[c]->prepareDerivative(iterate_, definite); });
  };

  double measure = contactResidual(iterate_, residual);
  bool atIterate = true;  // rhs_ and the contact impulses belong to iterate_
  double bestMeasure = measure;
  best = iterate_;
  // Where a factorisation of K+ costs more than kKeepFactorAbovePIterations iterations with P
  // (about 24x24 quads and up), the factor of an earlier step is kept as the preconditioner
  // (refactorised when a solve with it is slow, as within a step): on Slope at 48x48, K+ was
  // factorised anew on 10 of 100 steps at 200 ms each, where the previous steps' factor served.
  bool factored = stiffnessFactored_ && keepStiffnessFactor_;
  stiffnessFactored_ = factored;  // (preconditionContact uses P until K+ is factorised)
  double forcing = 0.1, previous = 0.0;
  int lastIterations = 0, relaxed = 0, iteration = 0;
  bool clamped = false;  // the Jacobian's K: exact (P - Delta P) until a line search fails, then K+
  // K+ at the iterate, leaving the derivatives J's K uses prepared (the clamped ones already are).
  auto refactorStiffness = [&] {
    prepareDerivatives(true);
    factorizeStiffness();
    if (!clamped) prepareDerivatives(false);
  };
  if (trace)
    std::fprintf(stderr, "step %d: newton contact solve, residual %.3e\n", step_ + 1, measure);
  while (true) {
    stats_.residual = measure;
    stats_.converged = measure < solver.pdTolerance;
    if (stats_.converged || !std::isfinite(measure) || stats_.pdIterations >= solveLimit_) break;
    if (factored && lastIterations > kRefactorIterations)
      refactorStiffness();
    else
      prepareDerivatives(clamped);
    int changed = 0;
    timed(contactSolveModule_, [&] { changed = contacts.linearize(); });
    // Inexact Newton: the linear tolerance follows the residual's decrease (Eisenstat-Walker 2).
    if (previous > 0.0) {
      const double ratio = measure / previous;
      forcing =
          std::min(0.1, std::max({0.9 * ratio * ratio, 1e-6, 0.25 * solver.pdTolerance / measure}));
    }
    previous = measure;
    timed(solverModule_, [&] { rhs = -(massRoot_.cwiseInverse().asDiagonal() * residual); });
    // Each step starts with P as the preconditioner (enough where contacts pin the cloth's
    // normal motion, as on Slope); K+ is factorised once a solve with P is slow.
    const int budget = std::max(1, solveLimit_ - stats_.pdIterations);
    GmresResult linear =
        gmres_.solve(applyJacobian, precondition, rhs, step, forcing,
                     factored ? budget : std::min(budget, kPIterations), kGmresRestart);
    if (!factored && !linear.converged && stats_.pdIterations < solveLimit_) {
      factored = true;
      refactorStiffness();
      const int spent = linear.iterations;
      linear = gmres_.solve(applyJacobian, precondition, rhs, step, forcing,
                            std::max(1, solveLimit_ - stats_.pdIterations), kGmresRestart, true);
      linear.iterations += spent;
    }
    lastIterations = linear.iterations;
    // A non-finite direction (a singular block in J) is a failed one; trying it would leave
    // non-finite impulses in the contact solver, which warm-starts from them.
    const bool finite = step.allFinite();
    bool accepted = false;
    double trial = measure, alpha = 1.0;
    for (; finite && alpha > kMinStep && !accepted; alpha *= 0.5) {
      timed(solverModule_, [&] { accelerated_ = iterate_ + alpha * step; });
      trial = contactResidual(accelerated_, trialResidual);
      accepted = trial <= (1.0 - 1e-4 * alpha) * measure;
    }
    if (accepted) {
      alpha *= 2.0;  // (the loop halved it once more)
      relaxed = 0;
    } else if (finite && relaxed < kRelaxedSteps) {
      alpha = 1.0;
      timed(solverModule_, [&] { accelerated_ = iterate_ + step; });
      trial = contactResidual(accelerated_, trialResidual);
      accepted = std::isfinite(trial) && trial < kRelaxedGrowth * bestMeasure;
      relaxed += accepted;
    }
    ++iteration;
    if (trace)
      std::fprintf(stderr,
                   "  %2d: %2d branch changes, gmres %3d (%.1e), step %.3f%s, residual %.3e -> "
                   "%.3e, %d solves\n",
                   iteration, changed, linear.iterations, linear.residual, accepted ? alpha : 0.0,
                   relaxed > 0 && accepted ? " (non-monotone)" : "", measure, trial,
                   stats_.pdIterations);
    atIterate = accepted;
    // A failed line search with the exact K: the direction was nearly singular, not wrong (on the
    // crumpling corner the directional finite differences of G matched J d to O(alpha), while
    // single nodes were sent 0.4 m and G was already 28-fold off its linearisation at alpha =
    // 1e-3). K = P - Delta P is indefinite where the cloth is compressed and buckles; the rest of
    // the step uses the clamped K+ (the preconditioner's matrix) in J, which keeps the elastic
    // part of every direction a descent one, at linear convergence. Exact K is tried first
    // because it converges quadratically where it is definite.
    if (!accepted && !clamped) {
      clamped = true;
      measure = contactResidual(iterate_, residual);
      atIterate = true;
      continue;
    }
    if (!accepted) break;  // stalled: the best iterate is the result
    iterate_.swap(accelerated_);
    residual.swap(trialResidual);
    measure = trial;
    if (measure < bestMeasure) {
      bestMeasure = measure;
      best = iterate_;
    }
  }
  if (!(measure <= bestMeasure)) {
    iterate_ = best;
    atIterate = false;
  }
  if (!atIterate) measure = contactResidual(iterate_, residual);
  if (trace) traceResidualNodes(residual);
  stats_.residual = measure;
  stats_.converged = measure < solver.pdTolerance;
  // The step's result is the checked iterate itself (its contacts are the recorded ones). One PD
  // global solve past it, as the PD iteration ends, would not be a contraction with the law mass
  // m~: for a stuck node it maps a displacement error d to (I - P^-1 M~) d, which grows smooth
  // errors by up to P_ii / m_i.
  timed(solverModule_, [&] { global_ = iterate_; });
}

const StepStats& Simulator::step() {
  const double h2 = h_ * h_;
  const double t1 = time_ + h_;
  const SolverSettings& solver = scene_.solver;
  stats_ = StepStats{};
  stats_.step = step_ + 1;
  stats_.time = t1;
  stats_.moduleSeconds.assign(moduleNames_.size(), 0.0);
  solveLimit_ = solver.pdIterations;

  // External forces at the end of the step (implicit Euler, Eqs. 1-2).
  force_.setZero();
  for (std::size_t f = 0; f < forces_.size(); ++f)
    timed(forceModule_[f], [&] { forces_[f]->accumulate(t1, force_); });
  for (std::size_t c = 0; c < constraints_.size(); ++c)
    timed(constraintModule_[c], [&] { constraints_[c]->beginStep(t1, x_); });

  timed(solverModule_, [&] {
    // y = x_n + h v_n + h^2 M^{-1} f_ext (Eq. 3)
    y_ = x_ + h_ * v_ + h2 * (inverseMass_.asDiagonal() * force_);
    massY_ = model_.mass.asDiagonal() * y_;
    // Warm start: the displacement the internal forces caused last step (x_n - y_{n-1}) changes
    // slowly, and carries the slow, bending-like modes that PD is slowest to converge.
    iterate_ = y_ + warmStart_;
    if (solver.acceleration == Acceleration::Anderson) anderson_.restart();
  });

  if (contact_) {
    detectContacts(time_, t1);
    const bool newton = solver.contact == ContactMethod::ActiveSet;
    if (newton && !contact_->activeSet().empty())
      solveNewtonWithContact();
    else if (newton)
      solveNewton();
    else
      solveWithPerNodeContact();
    // Detection saw the predicted path only (DiffCloth Eq. 9's frames from x_n, v_n); where the
    // path the solve took strays from it, contacts it meets that the set lacks are added and the
    // step is solved again from its result, each pass with a fresh iteration budget.
    for (int pass = 0; pass < kMissedContactPasses && !newton; ++pass) {
      int added = 0;
      timed(contactDetectionModule_ >= 0 ? contactDetectionModule_ : selfCollisionModule_, [&] {
        change_ = global_ - x_;
        added = contact_->addMissedContacts(x_, predicted_, change_);
      });
      if (added == 0) break;
      stats_.lateContacts += added;
      timed(contactSolveModule_, [&] { contact_->prepareSolve(contactLawMass_); });
      timed(solverModule_, [&] { iterate_ = global_; });
      solveLimit_ = stats_.pdIterations + solver.pdIterations;
      solveWithPerNodeContact();
    }
    timed(contactSolveModule_, [&] {
      if (newton)
        contact_->activeSet().record(lastContacts_);
      else
        contact_->record(lastContacts_);
      countBranches(lastContacts_, stats_);
      lastContacts_.sweeps = stats_.contactSweeps;
    });
    // The recorded impulses feed the output (contact_forces.npy) and the backward pass.
    for (const ContactPoint& p : lastContacts_.points)
      if (!p.impulse.allFinite() || !p.velocity.allFinite())
        throw NumericalError(
            step_ + 1, "contact_solve",
            "non-finite contact impulse or velocity at node " + std::to_string(p.node));
  } else if (solver.method == SolverMethod::Newton) {
    solveNewton();
  } else {
    solveProjectiveDynamics();
  }

  // The last global solution is the step's result (one PD iteration past the checked iterate).
  if (!global_.allFinite()) diagnoseNonFinite(x_);
  v_ = (global_ - x_) / h_;
  x_ = global_;
  warmStart_ = x_ - y_;
  time_ = t1;
  ++step_;
  const double maxSpeed = std::sqrt(v_.rowwise().squaredNorm().maxCoeff());
  if (!(maxSpeed < kBlowUpSpeed))
    throw NumericalError(step_, "solver",
                         "velocity " + std::to_string(maxSpeed) + " m/s: the integration blew up");
  return stats_;
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
  for (const auto& force : forces_) {
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
    trajectory.moduleNames = moduleNames_;
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
