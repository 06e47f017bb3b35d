#pragma once
// The forward simulator: Projective Dynamics cloth (DiffCloth Sec. 3.1) with the modules the
// scene names and nothing else. Owns the prefactorised system matrix P (Eq. 7).
//
// Solvers: the step's solve is a strategy (StepSolver.h) the scene's solver.method (without
// contact) or solver.contact (with obstacles or self-collision) chooses; all solve the
// implicit-Euler equations (Eq. 3), with contact the Signorini-Coulomb law of Eq. 8 for every
// detected contact. The simulator builds the modules, starts each step, detects contacts,
// delegates the solve, checks for non-finite values and advances.

#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/Model.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>
#include <weft/record/Substep.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/Scene.h>

#include <Eigen/SparseCore>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace weft {
namespace collision {
class ImpactZoneResponse;
}

// The engine's internals the simulator owns (private headers of the engine).
class AttachmentConstraint;
class ExternalForce;
class FrictionalContact;
class ModuleTimer;
class ProjectiveConstraint;
class StepSolver;
struct StepContext;
class SystemMatrix;

class Simulator {
 public:
  // Builds the modules the model's scene names and factorises P; the simulator keeps the model.
  explicit Simulator(std::shared_ptr<const Model> model);
  // The same for a scene compiled here (Model::compile). Throws InputError for an obstacle mesh
  // without triangles.
  explicit Simulator(const Scene& scene);
  ~Simulator();

  const Model& model() const { return *compiled_; }
  const std::shared_ptr<const Model>& sharedModel() const { return compiled_; }
  const Scene& scene() const { return scene_; }
  const ClothModel& cloth() const { return model_; }
  const NodeMatrix& positions() const { return x_; }
  const NodeMatrix& velocities() const { return v_; }
  double time() const { return time_; }
  int stepIndex() const { return step_; }
  double dt() const { return h_; }

  // Advances one step. Throws NumericalError naming step, module and quantity on NaN/Inf or
  // on a blow-up.
  const StepStats& step();
  // Runs `steps` steps from the current state, recording into `trajectory` (which gets the
  // current state and the model first if it is empty). `progress` is called after every step.
  void run(int steps, Trajectory& trajectory,
           const std::function<void(const StepStats&)>& progress = nullptr);

  // Continues from another state: positions x and velocities v (m x 3) at state `step` (time
  // step * dt), the solver's warm start dropped. For checks that perturb a recorded state
  // (finite differences of dL/dx_n); contact warm starts are not carried over, so use it where
  // the forward solve is converged tightly enough not to depend on its start.
  void restart(int step, const NodeMatrix& x, const NodeMatrix& v);

  // Drives handle `handle` (in model().handles()' order): from the next step on, its nodes'
  // targets are their initial positions + offset (a translation held over the whole step, each
  // piece of a split step included) until it is driven again; its trajectory no longer applies.
  // What a policy acting between steps sets (DiffCloth Sec. 6.5, the end effectors' next
  // positions). Throws std::out_of_range for a handle the scene does not have.
  void driveHandle(int handle, const Vec3& offset);

  // Modules built for this scene, in a fixed order, with their accumulated seconds.
  const std::vector<std::string>& moduleNames() const;
  const std::vector<double>& moduleSeconds() const;
  const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints() const {
    return constraints_;
  }
  const std::vector<std::unique_ptr<ExternalForce>>& forces() const { return compiled_->forces(); }
  // The scene's contact, or null when it has no obstacles and no self-collision.
  const FrictionalContact* contact() const { return contact_.get(); }
  // The impact-zone response (self_collision.model "impact_zones"), or null when the scene has
  // none; through it a benchmark or a test observes each step's zones (setObserver).
  collision::ImpactZoneResponse* impactZoneResponse() { return impactZones_.get(); }
  // The contacts of the last step (empty before the first step or without contact); of its last
  // piece when it was split.
  const StepContacts& lastContacts() const { return lastContacts_; }
  // The pieces of the last step when adaptive time stepping split it (empty when solved whole).
  const std::vector<Substep>& lastSubsteps() const { return lastSubsteps_; }
  // The one-coordinate system matrix M + h^2 sum_i w_i A_i^T A_i (P = this (x) I_3).
  const Eigen::SparseMatrix<double>& systemMatrix() const;

 private:
  // The solve at h = dt / 2^halvings (level 0: the scene's dt): the model compiled at that h,
  // its P, the solves' shared state and the step solver. Finer levels are built when a step
  // first needs them.
  struct Level;
  Level& level(int halvings);
  // Solves [t0, t0 + h] at `level` from the current state into the level's StepContext::global;
  // nothing advances. Returns the attempt's stats.
  const StepStats& attempt(Level& level, double t0);
  // Advances the state to the level's last attempt.
  void accept(Level& level, StepStats& total);
  // Solves [t0, t0 + 2 h] of `halvings` - 1 as two pieces at `halvings` (first split down to
  // `first` without an attempt), each split further while it does not converge and maxHalvings
  // allows; accumulates into `total`. Sets `failedFirst` when a piece at `first` failed.
  void subdivide(int halvings, int first, double t0, StepStats& total, bool& failedFirst);
  // The level the next step starts at (step()).
  void chooseNextStart(int first, bool failedFirst);
  void detectContacts(Level& level, double t0, double t1);
  void diagnoseNonFinite(const NodeMatrix& lastGood, double t1) const;

  std::shared_ptr<const Model> compiled_;
  const Scene& scene_;
  const ClothModel& model_;
  double h_;
  std::unique_ptr<ModuleTimer> timer_;
  std::vector<std::unique_ptr<ProjectiveConstraint>> constraints_;
  AttachmentConstraint* handles_ = nullptr;  // the handles family in constraints_, if any
  std::vector<int> constraintModule_;
  std::vector<int> forceModule_;  // the timing module of each of the model's forces
  int solverModule_ = -1;
  std::unique_ptr<FrictionalContact> contact_;
  int contactDetectionModule_ = -1, selfCollisionModule_ = -1, contactSolveModule_ = -1;
  std::unique_ptr<collision::ImpactZoneResponse> impactZones_;  // self_collision "impact_zones"
  int impactZoneModule_ = -1;
  StepContacts lastContacts_;
  std::vector<Substep> lastSubsteps_;
  StepStats stepStats_;  // the last step's, over its pieces

  NodeMatrix x_, v_;
  double time_ = 0.0;
  int step_ = 0;
  NodeMatrix warmStart_;        // x_n - y_{n-1}
  double warmStartStep_ = 0.0;  // the h warmStart_ was made with
  NodeMatrix force_;
  NodeMatrix predicted_;  // the displacement detection predicted (contact scenes only)

  std::vector<std::unique_ptr<Level>> levels_;  // by halvings
  int nextStart_ = 0;   // the halvings the next step's first attempts are made at
  int cleanSteps_ = 0;  // steps in a row solved at their first level (chooseNextStart)
};

}  // namespace weft
