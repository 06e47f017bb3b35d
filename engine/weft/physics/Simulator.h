#pragma once
// The forward simulator: Projective Dynamics cloth (DiffCloth Sec. 3.1) with the modules the
// scene names and nothing else. Owns the prefactorised system matrix P (Eq. 7).
//
// Solvers. Without contact (solver.method): Newton-PCG (default) or PD with Anderson
// acceleration, both minimising the implicit-Euler energy g (Eq. 3).
// With contact (obstacles or self-collision; solver.contact), both solve the Signorini-Coulomb
// law of Eq. 8 for every detected contact:
//  - "pd" (default): DiffCloth's velocity-form PD with the per-node contact solve inside every
//    global step (Sec. 3.2, Eqs. 10-12, notes Sec. 2.1; ContactSolver.h). solver.acceleration
//    applies: "anderson" (default) mixes the iterates with a residual-based safeguard, "none"
//    runs plain PD. It stops on the same residual, which then includes the contact impulse (see
//    solveWithContact); on stiff cloth it often reaches the iteration cap first.
//  - "active_set" (experimental): Newton-PCG on g with the contacts as an active set of linear
//    constraints (ActiveContactSet.h): feasible iterates, multipliers as contact impulses, branch
//    updates by Eq. 8, slip friction lagged. No contact ends a step on the wrong side of its
//    constraint, whatever the iteration count; the lagged friction and branch cycling still
//    make many steps reach the iteration cap.
//  - "newton": semismooth Newton on the residual of the "pd" iteration's fixed point (see
//    solveContactNewton): the same law and the same solution, reached in a few Newton steps
//    where the PD iteration converges linearly. The law is solved with the mass sqrt(m_i P_ii)
//    (which changes the iterates, not the solution), and the linear solves are preconditioned by
//    P, or, once that is slow, by a factorisation of the clamped Hessian K+: P leaves one soft
//    out-of-plane mode per node that PD and P-preconditioned Krylov methods converge slowly on.
//    Steps without contacts take the same path.

#include <weft/contact/FrictionalContact.h>
#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/AndersonAccelerator.h>
#include <weft/physics/ExternalForce.h>
#include <weft/physics/Gmres.h>
#include <weft/physics/HessianAssembly.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/SparseCholesky.h>
#include <weft/record/StepStats.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/Scene.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace weft {

class Simulator {
 public:
  // Builds the modules the scene names and factorises P. The scene must outlive the simulator.
  // Throws InputError for scene features this build cannot simulate.
  explicit Simulator(const Scene& scene);
  ~Simulator();

  const Scene& scene() const { return scene_; }
  const ClothModel& model() const { return model_; }
  const NodeMatrix& positions() const { return x_; }
  const NodeMatrix& velocities() const { return v_; }
  double time() const { return time_; }
  int stepIndex() const { return step_; }
  double dt() const { return h_; }

  // Advances one step. Throws NumericalError naming step, module and quantity on NaN/Inf or
  // on a blow-up.
  const StepStats& step();
  // Runs `steps` steps from the current state, recording into `trajectory` (which gets the
  // current state first if it is empty). `progress` is called after every step.
  void run(int steps, Trajectory& trajectory,
           const std::function<void(const StepStats&)>& progress = nullptr);

  // Continues from another state: positions x and velocities v (m x 3) at state `step` (time
  // step * dt), the solver's warm start dropped. For checks that perturb a recorded state
  // (finite differences of dL/dx_n); contact warm starts are not carried over, so use it where
  // the forward solve is converged tightly enough not to depend on its start.
  void restart(int step, const NodeMatrix& x, const NodeMatrix& v);

  // Modules built for this scene, in a fixed order, with their accumulated seconds.
  const std::vector<std::string>& moduleNames() const { return moduleNames_; }
  const std::vector<double>& moduleSeconds() const { return moduleSeconds_; }
  const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints() const {
    return constraints_;
  }
  const std::vector<std::unique_ptr<ExternalForce>>& forces() const { return forces_; }
  // The scene's contact, or null when it has no obstacles and no self-collision.
  const FrictionalContact* contact() const { return contact_.get(); }
  // The contacts of the last step (empty before the first step or without contact).
  const StepContacts& lastContacts() const { return lastContacts_; }
  // The one-coordinate system matrix M + h^2 sum_i w_i A_i^T A_i (P = this (x) I_3).
  const Eigen::SparseMatrix<double>& systemMatrix() const { return system_; }

 private:
  int addModule(const std::string& name);
  // Projections of every constraint at x, into projections_; returns g(x)'s constraint and
  // inertia energy, or 0 without `energy` (then families whose projections are all zero are
  // skipped: they only contribute to it).
  double localStep(const NodeMatrix& x, bool energy = true);
  template <class Fn>
  void timed(int module, Fn&& fn);
  void globalStep();
  // Measures the residual of the last global step; true (and stats_.converged) below tolerance.
  bool checkConvergence();
  void solveProjectiveDynamics();
  // Newton-PCG iterations until the residual is below tolerance (true) or the solve budget is
  // spent. With activeContacts_ set, iterates stay on its constraints and its slip friction acts.
  bool iterateNewton();
  void solveNewton() { iterateNewton(); }
  void solveNewtonWithContact();
  void detectContacts(double t0, double t1);
  // rhs_ = b(x) + h r(f(x)) with the contact solve at x, and P x into systemTimesX.
  void assembleContactRhs(const NodeMatrix& x, NodeMatrix& systemTimesX);
  void contactGlobalStep();
  // The step's solve with the per-node contact law: solveContactNewton or solveWithContact, from
  // iterate_, until stats_.pdIterations reaches solveLimit_.
  void solveWithPerNodeContact();
  void solveWithContact();
  // G(x) = P x - b(x) - h r(f(x)) into `residual` (the contact impulses r from the per-node law
  // at x, rhs_ = b(x) + h r); returns its mass-weighted RMS (residualOf's measure).
  double contactResidual(const NodeMatrix& x, NodeMatrix& residual);
  void solveContactNewton();
  void traceResidualNodes(const NodeMatrix& residual) const;  // WEFT_CONTACT_TRACE
  void finishWithPerNodeIterations();
  // The Newton contact solve's preconditioner: a CHOLMOD factor of the 3m x 3m clamped Hessian
  // K+ = P - Delta P+ (the `definite` projection derivatives), assembled from the constraints'
  // element blocks (HessianAssembly). False when the factorisation failed (the preconditioner then
  // falls back to P).
  bool factorizeStiffness();
  // z = B r for the GMRES of solveContactNewton (r, z mass-scaled as there; one "solve").
  void preconditionContact(const NodeMatrix& scaled, NodeMatrix& z);
  void multiplySystem(const NodeMatrix& in, NodeMatrix& out) const;  // one-coordinate P, 3 columns
  void multiplyNewtonMatrix(const NodeMatrix& in, NodeMatrix& out);
  double residualOf(
      const NodeMatrix& systemTimesChange) const;  // the convergence measure of P (x_global - x)
  void assembleAndFactorize();
  void diagnoseNonFinite(const NodeMatrix& lastGood) const;

  const Scene& scene_;
  ClothModel model_;
  double h_;
  std::vector<std::unique_ptr<ProjectiveConstraint>> constraints_;
  std::vector<int> constraintModule_;
  std::vector<std::unique_ptr<ExternalForce>> forces_;
  std::vector<int> forceModule_;
  int solverModule_ = -1;
  std::unique_ptr<FrictionalContact> contact_;
  int contactDetectionModule_ = -1, selfCollisionModule_ = -1, contactSolveModule_ = -1;
  StepContacts lastContacts_;
  ActiveContactSet* activeContacts_ = nullptr;  // during a Newton step with contact
  std::vector<std::string> moduleNames_;
  std::vector<double> moduleSeconds_;

  Eigen::SparseMatrix<double> system_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> systemRows_;  // the same, for row-parallel products
  Eigen::VectorXd inverseMass_;
  Eigen::VectorXd massRoot_;  // M^1/2, the scaling of the Newton contact solve's residual
  // The Newton contact solve's law mass m~ (ContactSolver::setContacts): sqrt(m_i P_ii).
  Eigen::VectorXd lawMass_;
  const Eigen::VectorXd* contactLawMass_ = nullptr;  // &lawMass_ during a Newton contact step
  SparseCholesky cholesky_;
  AndersonAccelerator anderson_;

  NodeMatrix x_, v_;
  double time_ = 0.0;
  int step_ = 0;
  StepStats stats_;
  int solveLimit_ = 0;  // the current solve stops when stats_.pdIterations reaches it

  // Work buffers, allocated once.
  NodeMatrix warmStart_;  // x_n - y_{n-1}
  NodeMatrix force_, y_, massY_, iterate_, global_, accelerated_, change_, rhs_, residualVector_;
  NodeMatrix direction_, cgResidual_, cgPreconditioned_, cgSearch_, cgProduct_;
  NodeMatrix freeMomentum_, plainIterate_, fullResidual_;  // contact scenes only
  NodeMatrix predicted_;  // the displacement detection predicted (contact scenes only)
  NodeMatrix lawInput_, pinnedPart_, newtonResult_;     // solver.contact = "newton" only
  std::unique_ptr<HessianAssembly> stiffnessAssembly_;  // K+ (factorizeStiffness)
  Eigen::SparseMatrix<double> stiffness_;
  SparseCholesky stiffnessCholesky_{SparseCholesky::Use::Preconditioner};
  bool stiffnessFactored_ = false;
  // A factorisation of K+ costs so many iterations with P that a step starts from the previous
  // step's factor (solveContactNewton).
  bool keepStiffnessFactor_ = false;
  NodeMatrix coupling_;
  Gmres gmres_;
  std::vector<NodeMatrix> projections_, derivativeRows_;
  double totalMass_ = 0.0;
};

}  // namespace weft
