#include <weft/physics/Simulator.h>

#include <weft/core/Error.h>
#include <weft/physics/AttachmentConstraint.h>
#include <weft/physics/BendingConstraint.h>
#include <weft/physics/GravityForce.h>
#include <weft/physics/NodalForces.h>
#include <weft/physics/StretchConstraint.h>
#include <weft/physics/WindForce.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace weft {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A speed no cloth reaches unless the integration has blown up.
constexpr double kBlowUpSpeed = 1e5;  // m/s

}  // namespace

Simulator::Simulator(const Scene& scene) : scene_(scene), model_(buildClothModel(scene)), h_(scene.time.dt) {
  if (!scene.obstacles.empty())
    throw InputError(scene.file, "obstacles", "obstacle contact is not available in this build yet");
  if (scene.hasSelfCollision())
    throw InputError(scene.file, "cloths.self_collision", "self-collision is not available in this build yet");

  solverModule_ = addModule("solver");
  // Constraint modules: only those with at least one instance.
  auto addConstraint = [this](std::unique_ptr<ProjectiveConstraint> c) {
    if (c->rowCount() == 0) return;
    constraintModule_.push_back(addModule(c->name()));
    constraints_.push_back(std::move(c));
  };
  addConstraint(std::make_unique<StretchConstraint>(makeStretchConstraint(scene, model_)));
  addConstraint(std::make_unique<BendingConstraint>(makeBendingConstraint(scene, model_)));
  addConstraint(std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, model_, false)));
  addConstraint(std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, model_, true)));

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

  const int m = model_.nodeCount();
  x_ = model_.rest.vertices;
  v_.resize(m, 3);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (int i = model_.vertexOffset[c]; i < model_.vertexOffset[c + 1]; ++i)
      v_.row(i) = scene.cloths[c].initialVelocity.transpose();
  for (auto* buf : {&force_, &y_, &massY_, &iterate_, &global_, &accelerated_, &change_, &rhs_})
    buf->setZero(m, 3);
  for (const auto& c : constraints_) projections_.emplace_back(NodeMatrix::Zero(c->rowCount(), 3));
  if (scene.solver.acceleration == Acceleration::Anderson) anderson_.reset(3 * m, scene.solver.andersonWindow);

  const auto start = Clock::now();
  assembleAndFactorize();
  moduleSeconds_[solverModule_] += secondsSince(start);
}

Simulator::~Simulator() = default;

int Simulator::addModule(const std::string& name) {
  moduleNames_.push_back(name);
  moduleSeconds_.push_back(0.0);
  return static_cast<int>(moduleNames_.size()) - 1;
}

void Simulator::assembleAndFactorize() {
  const int m = model_.nodeCount();
  Eigen::SparseMatrix<double> mass(m, m);
  std::vector<Eigen::Triplet<double>> diag;
  for (int i = 0; i < m; ++i) diag.emplace_back(i, i, model_.mass[i]);
  mass.setFromTriplets(diag.begin(), diag.end());
  system_ = mass;
  for (const auto& c : constraints_) system_ += (h_ * h_) * c->weightedGram();
  system_.makeCompressed();
  if (!cholesky_.factorize(system_))
    throw NumericalError(0, "solver", "system matrix P is not positive definite");
}

double Simulator::localStep(const NodeMatrix& x) {
  // Inertia term of g (DiffCloth Eq. 3): |x - y|^2_M / (2 h^2).
  double energy = 0.5 / (h_ * h_) * (model_.mass.asDiagonal() * (x - y_)).cwiseProduct(x - y_).sum();
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const auto start = Clock::now();
    energy += constraints_[c]->project(x, projections_[c]);
    const double s = secondsSince(start);
    moduleSeconds_[constraintModule_[c]] += s;
    stats_.moduleSeconds[constraintModule_[c]] += s;
  }
  return energy;
}

const StepStats& Simulator::step() {
  const double h2 = h_ * h_;
  const double t1 = time_ + h_;
  const int m = model_.nodeCount();
  const SolverSettings& solver = scene_.solver;
  stats_ = StepStats{};
  stats_.step = step_ + 1;
  stats_.time = t1;
  stats_.moduleSeconds.assign(moduleNames_.size(), 0.0);
  auto timed = [this](int module, auto&& fn) {
    const auto start = Clock::now();
    fn();
    const double s = secondsSince(start);
    moduleSeconds_[module] += s;
    stats_.moduleSeconds[module] += s;
  };

  // External forces at the end of the step (implicit Euler, Eqs. 1-2).
  force_.setZero();
  for (std::size_t f = 0; f < forces_.size(); ++f)
    timed(forceModule_[f], [&] { forces_[f]->accumulate(t1, force_); });
  for (std::size_t c = 0; c < constraints_.size(); ++c)
    timed(constraintModule_[c], [&] { constraints_[c]->beginStep(t1); });

  timed(solverModule_, [&] {
    // y = x_n + h v_n + h^2 M^{-1} f_ext (Eq. 3)
    y_ = x_ + h_ * v_ + h2 * (model_.mass.cwiseInverse().asDiagonal() * force_);
    massY_ = model_.mass.asDiagonal() * y_;
    iterate_ = y_;
    if (solver.acceleration == Acceleration::Anderson) anderson_.restart();
  });

  const double totalMass = model_.mass.sum();
  double previousEnergy = std::numeric_limits<double>::infinity();
  bool accelerated = false;
  int k = 0;
  for (; k < solver.pdIterations; ++k) {
    double energy = localStep(iterate_);
    if (accelerated && !(energy <= previousEnergy)) {
      // Safeguard (Peng et al. 2018): the accelerated iterate raised the energy; take the plain
      // PD iterate instead, which never does (it minimises the surrogate of Eq. 6).
      iterate_ = global_;
      anderson_.restart();
      energy = localStep(iterate_);
    }
    previousEnergy = energy;
    double residual = 0.0;
    timed(solverModule_, [&] {
      // Global step (Eq. 7): P x = M y + h^2 sum_i w_i A_i^T p_i.
      rhs_ = massY_;
      for (std::size_t c = 0; c < constraints_.size(); ++c)
        rhs_.noalias() += h2 * (constraints_[c]->selectionTransposed() * projections_[c]);
      global_ = rhs_;
      cholesky_.solveInPlace(global_);
      // Residual at the iterate: P (x_global - x_k) = -h^2 grad g(x_k), as accelerations.
      change_ = global_ - iterate_;
      rhs_.noalias() = system_ * change_;
      residual = std::sqrt((rhs_.rowwise().squaredNorm().array() / model_.mass.array()).sum() / totalMass) / h2;
    });
    stats_.residual = residual;
    if (residual < solver.pdTolerance) {
      stats_.converged = true;
      ++k;
      break;
    }
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
  stats_.pdIterations = std::min(k, solver.pdIterations);

  // The plain global solution is the step's result (one PD iteration past the checked iterate).
  if (!global_.allFinite()) diagnoseNonFinite(x_);
  v_ = (global_ - x_) / h_;
  x_ = global_;
  time_ = t1;
  ++step_;
  const double maxSpeed = std::sqrt(v_.rowwise().squaredNorm().maxCoeff());
  if (!(maxSpeed < kBlowUpSpeed))
    throw NumericalError(step_, "solver", "velocity " + std::to_string(maxSpeed) + " m/s: the integration blew up");
  (void)m;
  return stats_;
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
    if (!p.allFinite()) throw NumericalError(step_ + 1, constraints_[c]->name(), "non-finite projection");
  }
  throw NumericalError(step_ + 1, "solver", "non-finite positions after the global solve");
}

void Simulator::run(int steps, Trajectory& trajectory, const std::function<void(const StepStats&)>& progress) {
  if (trajectory.positions.empty()) {
    trajectory.positions.push_back(x_);
    trajectory.velocities.push_back(v_);
    trajectory.moduleNames = moduleNames_;
  }
  trajectory.positions.reserve(trajectory.positions.size() + steps);
  trajectory.velocities.reserve(trajectory.velocities.size() + steps);
  for (int s = 0; s < steps; ++s) {
    const StepStats& st = step();
    trajectory.positions.push_back(x_);
    trajectory.velocities.push_back(v_);
    trajectory.steps.push_back(st);
    if (progress) progress(st);
  }
}

}  // namespace weft
