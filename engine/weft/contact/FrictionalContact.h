#pragma once
// The dry frictional contact of one scene (DiffCloth Sec. 3.2, Ly et al. 2020): its obstacles
// (analytic or mesh, static or kinematic), node-node self-collision when a cloth asks for it,
// and the per-node Signorini-Coulomb solve that the Simulator calls inside every PD iteration.
// Built only for scenes with obstacles or self-collision.
//
// Per step (Simulator::step):
//   beginStep             obstacles moved to the end-of-step pose
//   detectObstacles       contact set and frozen frames (module "contact_detection")
//   detectSelfCollisions  pairs and their Gauss-Seidel layers (module "self_collision")
//   then, with solver.contact = "pd", per PD iteration solve(f) and addImpulses (module
//   "contact_solve") and finally record; with "newton", the same per iterate plus the
//   linearisation of perNodeSolver(); with "active_set", the Simulator drives activeSet()
//   (ActiveContactSet.h) instead.

#include <weft/contact/ActiveContactSet.h>
#include <weft/contact/ContactLayering.h>
#include <weft/contact/ContactObstacle.h>
#include <weft/contact/ContactSolver.h>
#include <weft/contact/ObstacleContactDetector.h>
#include <weft/contact/SelfCollisionDetector.h>
#include <weft/model/ClothModel.h>

#include <memory>
#include <tuple>
#include <vector>

namespace weft {

class FrictionalContact {
 public:
  // `shapes`: one per scene obstacle, in scene order (Model::obstacleShapes).
  FrictionalContact(const Scene& scene, const ClothModel& model,
                    const std::vector<std::shared_ptr<const ObstacleShape>>& shapes);

  bool hasObstacles() const { return !obstacles_.empty(); }
  bool hasSelfCollision() const { return selfCollision_ != nullptr; }
  const std::vector<ContactObstacle>& obstacles() const { return obstacles_; }
  // Detection margin for obstacles (m): a quarter of the cloth's mean rest edge length.
  double obstacleMargin() const { return detector_->margin(); }

  void beginStep(double t0, double t1);
  // x: state at the start of the step; displacement: the predicted motion over the step.
  void detectObstacles(const NodeMatrix& x, const NodeMatrix& displacement);
  void detectSelfCollisions(const NodeMatrix& x, const NodeMatrix& displacement);
  // After a step's solve, the contacts that the path actually taken (x -> x + actual) violates
  // and detection from the predicted path (x -> x + predicted) missed, such as a node stopped by
  // a wall while its neighbour flies on into it: added to the set, their frames from x as
  // detection makes them; returns how many. The caller hands the set to the solver again and
  // solves the step anew. Violated: the step ends closer along the contact's normal than its
  // constraint allows, by more than kViolationTolerance of the detection margin (obstacles) or
  // collision distance (pairs). A family is not searched when no node strayed from its predicted
  // path by more than detection's margin covers (half the pairs' margin, the obstacles' margin).
  int addMissedContacts(const NodeMatrix& x, const NodeMatrix& predicted, const NodeMatrix& actual);
  // Hands the detected contacts to the per-node solver of solver.contact = "pd" and "newton"
  // (impulses start at zero), optionally with the mass the law is solved with
  // (ContactSolver::setContacts; default: the lumped mass).
  void prepareSolve(const Eigen::VectorXd* lawMass = nullptr);
  // Hands the detected contacts to the active set of solver.contact = "active_set"; x0 is the
  // start-of-step state and must stay unchanged during the step.
  void prepareActiveSet(const NodeMatrix& x0, double velocityTolerance) {
    activeSet_.reset(obstacleContacts_, pairs_, x0, model_.mass, h_, velocityTolerance);
  }
  ActiveContactSet& activeSet() { return activeSet_; }
  bool empty() const { return solver_.empty(); }

  // One contact solve of a PD iteration (ContactSolver.h); returns the sweeps done.
  int solve(const NodeMatrix& freeMomentum, double sweepTolerance);
  void addImpulses(double scale, NodeMatrix& rhs) const { solver_.addImpulses(scale, rhs); }
  double lastSweepChange() const { return solver_.lastChange(); }
  // The per-node solver itself, for the semismooth Newton contact solve (solver.contact =
  // "newton"), which also needs its linearisation (ContactSolver::linearize).
  ContactSolver& perNodeSolver() { return solver_; }

  void record(StepContacts& out) const { solver_.record(out); }
  // The deepest node of x (the step's end state) inside any obstacle's contact skin, against the
  // end-of-step poses: max over nodes and obstacles of skin - signed distance, 0 if none (m).
  double deepestPenetration(const NodeMatrix& x) const;
  int obstacleContactCount() const { return static_cast<int>(obstacleContacts_.size()); }
  int pairCount() const { return static_cast<int>(pairs_.size()); }

  // addMissedContacts adds a contact violated by more than this fraction of the obstacle margin
  // or collision distance (smaller violations are left for the next step's detection).
  static constexpr double kViolationTolerance = 0.01;
  // Gauss-Seidel sweeps allowed per PD iteration when contacts are coupled.
  static constexpr int kMaxSweeps = 16;

 private:
  void orderPairs();  // Gauss-Seidel layers of pairs_ (ContactLayering), obstacle nodes first

  const ClothModel& model_;
  double h_ = 0.0;
  std::vector<ContactObstacle> obstacles_;
  std::unique_ptr<ObstacleContactDetector> detector_;
  std::unique_ptr<SelfCollisionDetector> selfCollision_;
  ContactLayering layering_;
  ContactSolver solver_;
  ActiveContactSet activeSet_;
  std::vector<ContactPoint> obstacleContacts_, pairs_, found_;
  std::vector<std::tuple<int, int, int>>
      keys_;  // addMissedContacts' scratch: node, partner, obstacle
  std::vector<int> obstacleNodes_, layerStart_;
};

}  // namespace weft
