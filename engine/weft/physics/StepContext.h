#pragma once
// What every step solve works on (StepSolver.h): the scene's solver settings, the model, the
// constraints with their projections, the system matrix P and its factor, the module timing, the
// contact (contact scenes), the step's statistics and the work buffers, allocated once. The
// Simulator fills the step's start (y, M y, the first iterate) and reads the result from
// `global`; the solvers share the local and global steps of PD (DiffCloth Eqs. 6-7) and the
// convergence measure defined here.

#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/Model.h>
#include <weft/physics/ModuleTimer.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/SystemMatrix.h>
#include <weft/record/StepStats.h>

#include <memory>
#include <utility>
#include <vector>

namespace weft {

class ActiveContactSet;
class FrictionalContact;

struct StepContext {
  // `start` is the state the steps start from (x_n, kept by the Simulator); `contact` is null
  // without obstacles and self-collision. All must outlive the context.
  StepContext(const Model& compiled, const NodeMatrix& start,
              const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints,
              const std::vector<int>& constraintModule, SystemMatrix& system, ModuleTimer& timer,
              int solverModule, FrictionalContact* contact, int contactSolveModule);

  // The simulation's fixed parts.
  const SolverSettings& settings;
  const ClothModel& model;
  const double h;
  const NodeMatrix& start;  // x_n
  const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints;
  const std::vector<int>& constraintModule;  // the timing module of each constraint family
  SystemMatrix& system;
  ModuleTimer& timer;
  const int solverModule;
  FrictionalContact* const contact;
  const int contactSolveModule;  // -1 without contact
  Eigen::VectorXd inverseMass;
  Eigen::VectorXd massRoot;  // M^1/2, the scaling of the Newton contact solve's residual
  double totalMass = 0.0;

  // The step.
  StepStats stats;
  int solveLimit = 0;  // the current solve stops when stats.pdIterations reaches it
  // A failed attempt will be thrown away and solved again as two halves (adaptive time
  // stepping, Simulator::step): a solve that stalls gives up instead of spending the rest of its
  // budget on a fallback.
  bool splittable = false;
  NodeMatrix y, massY;  // y = x_n + h v_n + h^2 M^-1 f_ext (Eq. 3) and M y
  NodeMatrix iterate;   // the solve's current iterate
  NodeMatrix global;    // the last global solution: the step's result once the solve returns
  // Work buffers, allocated once.
  NodeMatrix change, rhs, residualVector, accelerated;
  NodeMatrix direction, cgResidual, cgPreconditioned, cgSearch, cgProduct;
  NodeMatrix freeMomentum, plainIterate, fullResidual;  // contact scenes only
  std::vector<NodeMatrix> projections, derivativeRows;  // per constraint family

  template <class Fn>
  void timed(int module, Fn&& fn) {
    timer.timed(module, std::forward<Fn>(fn));
  }
  // Projections of every constraint at x, into `projections`; returns g(x)'s constraint and
  // inertia energy, or 0 without `energy` (then families whose projections are all zero are
  // skipped: they only contribute to it).
  double localStep(const NodeMatrix& x, bool energy = true);
  // Global step (Eq. 7) from `iterate` with the last local step's projections, into `global`
  // and `change` (= global - iterate); `contacts` (the active-set solve) adds its slip friction.
  void globalStep(ActiveContactSet* contacts = nullptr);
  // Measures the residual of the last global step into stats.residual; true (and
  // stats.converged) below tolerance. With `contacts`, only the free directions count.
  bool checkConvergence(ActiveContactSet* contacts = nullptr);
  // The convergence measure of P (x_global - x): a mass-weighted RMS acceleration (m/s^2).
  double residualOf(const NodeMatrix& systemTimesChange) const;
  // out = K in, K = P - Delta P (Sec. 4.1) with the prepared projection derivatives, plus the
  // active set's friction Hessian when given.
  void multiplyNewtonMatrix(const NodeMatrix& in, NodeMatrix& out,
                            ActiveContactSet* contacts = nullptr);
  // Prepares every family's projection derivative at `iterate` (clamped when `definite`).
  void prepareDerivatives(bool definite);
};

}  // namespace weft
