#pragma once
// The step's contacts as an active set of linear constraints, for the Newton solver with contact
// (solver.contact = "active_set", experimental). It solves the same Signorini-Coulomb law as the
// paper's per-node solve inside PD (DiffCloth Eq. 8; ContactSolver.h, solver.contact = "pd"), but
// with the elastic part converged by Newton instead of PD iterations, which on stiff cloth stop at
// the iteration cap long before the contact impulses settle.
//
// Each contact is in one branch of Eq. 8, and the branch says which part of the contact's
// end-of-step velocity u = v_a (- v_b) - reference is prescribed (see ContactPoint.h for the
// gap-aware reference):
//   take-off  nothing                   (r = 0)
//   stick     u = 0, three rows          (r = multiplier / h)
//   slip      u_N = 0, one row           (r = multiplier n / h + friction on the cone)
// In positions, each row is dir . (x_a - x_b) = target, i.e. C x = c. Between branch updates the
// step is an equality-constrained minimisation of g (Eq. 3) plus the potential of the slip
// friction; Newton-PCG keeps its iterates feasible by projecting positions onto {C x = c} and
// directions onto {C d = 0} with the orthogonal projector I - C^T (C C^T)^-1 C (one sparse LDLT
// of the small C C^T per active set). The multipliers of the converged solve are the contact
// impulses, and the branch update checks them and the velocities against Eq. 8:
//   take-off with u_N < 0                        -> stick (slip if mu = 0)
//   stick with r_N < 0                           -> take-off
//   stick with |r_T| > mu r_N                    -> slip, friction mu r_N along r_T's direction
//   slip with r_N < 0                            -> take-off
//   slip with u_T stopped or along the friction  -> stick
//   slip otherwise: friction -mu r_N u_T / |u_T|, implicit in u_T (the gradient of the convex
//   potential mu r_N |u_T|, whose Hessian, floored near rest, Newton uses) and lagged in r_N,
//   updated on settled solves.
// The step is done when no branch changes and the friction changed by less than the tolerance.
// Positions are always feasible for the current branches, so whatever the iteration count, no
// contact ends the step on the wrong side of its constraint.

#include <weft/record/ContactPoint.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <vector>

namespace weft {

class ActiveContactSet {
 public:
  // The step's contacts (obstacle contacts, then pairs) with the start-of-step positions x0,
  // which must stay alive and unchanged during the step.
  void reset(const std::vector<ContactPoint>& obstacleContacts,
             const std::vector<ContactPoint>& pairs, const NodeMatrix& x0,
             const Eigen::VectorXd& mass, double h, double velocityTolerance);
  bool empty() const { return contacts_.empty(); }

  // First branches from a predicted end-of-step position: contacts it would violate start in
  // the branch their node's obstacle contact ended the last step in, else in stick (slip when
  // mu = 0); the others in take-off. Rebuilds the rows.
  void guessBranches(const NodeMatrix& x);
  bool hasRows() const { return !rows_.empty(); }

  // x <- the nearest positions (Euclidean) with C x = c.
  void projectPositions(NodeMatrix& x) const;
  // d <- its component in {C d = 0}.
  void projectDirection(NodeMatrix& d) const;
  // The recorded velocities u from the final positions.
  void refreshVelocities(const NodeMatrix& x);
  // Slip friction at positions x (impulse -mu r_N u_T / |u_T| with r_N lagged):
  // residual += h * friction impulses.
  void addFriction(const NodeMatrix& x, double h, NodeMatrix& residual) const;
  // Its potential, sum mu r_N |u_T| (convex in x), to add to g (Eq. 3) in the line search.
  double frictionPotential(const NodeMatrix& x) const;
  // Its Hessian (times h^2, the scale of the Newton matrix P - Delta P) at x, applied: out += H d.
  void prepareFrictionHessian(const NodeMatrix& x);
  void addFrictionHessian(const NodeMatrix& d, NodeMatrix& out) const;

  // Branch update at the end of a converged solve. `residual` = b(x) + h F - P x (the momentum
  // imbalance including friction, kg m); the rows' multipliers are the least-squares solution of
  // C^T lambda = -residual. Returns the number of contacts whose branch changed; lastChange()
  // is then the largest friction change (as a velocity, m/s). `settled`: the elastic solve has
  // converged for the current branches; only then are slip contacts judged (slide, friction
  // direction and magnitude), otherwise they keep their friction (lastChange() = 0).
  int update(const NodeMatrix& x, const NodeMatrix& residual, double velocityTolerance,
             bool settled);
  double lastChange() const { return lastChange_; }
  // Contacts that the last settled update found violating Eq. 8 but kept in their branch because
  // they had switched too often this step (the anti-cycling rule in update()); a step with any
  // is not converged.
  int blocked() const { return blocked_; }

  void record(StepContacts& out) const;

 private:
  // A contact in the solve: its record (the detected frame; the branch, impulse (on node,
  // friction included), velocity u at the last update and mass the solve leaves) and the solve's
  // own state.
  struct Contact {
    ContactPoint point;
    double slipLimit = 0.0;  // slip: mu r_N, the friction impulse's size (lagged)
    int flips = 0;           // branch switches this step
    // Slip: u_T and max(|u_T|, eps) where the friction Hessian was prepared.
    Vec3 hessianSlide = Vec3::Zero();
    double hessianNorm = 0.0;
  };
  struct Row {
    int a, b, contact;
    Vec3 dir;
    double target;
  };
  Vec3 relativeVelocity(const Contact& c, const NodeMatrix& x) const;
  Vec3 slide(const Contact& c, const NodeMatrix& x) const;  // tangential part of u
  Vec3 frictionImpulse(const Contact& c, const NodeMatrix& x) const;
  bool violatesLaw(const Contact& c, double velocityTolerance) const;
  void buildRows();
  void multipliers(const NodeMatrix& v, Eigen::VectorXd& lambda) const;  // (C C^T)^-1 C v
  void project(NodeMatrix& v, bool affine) const;  // onto {C v = c} (affine) or {C v = 0}

  std::vector<Contact> contacts_;
  struct Previous {  // a node's obstacle contact at the end of the last step
    ContactBranch branch = ContactBranch::None;
    double slipLimit = 0.0;
  };
  std::vector<Previous> previous_;  // per node
  std::vector<int> rememberedNodes_;
  std::vector<Row> rows_;
  const NodeMatrix* x0_ = nullptr;  // start-of-step positions (the Simulator's state)
  double h_ = 0.0;
  double smoothing_ = 0.0;  // eps (m/s): floor of |u_T| in the friction Hessian, and stick speed
  double lastChange_ = 0.0;
  int blocked_ = 0;
  Eigen::SparseMatrix<double> gram_;  // C C^T
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> gramFactor_;
  mutable Eigen::VectorXd rowValues_, lambda_;
};

}  // namespace weft
