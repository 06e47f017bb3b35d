#pragma once
// The contact solve inside each PD iteration (DiffCloth Eq. 12, after Ly et al. 2020; notes
// Secs. 2.1, 2.2, 2.4). Given the free momentum f of every node (what M v would be without
// contact impulses, predicted with the diagonal mass M as in Eq. 12), it finds contact
// impulses r such that every contact's velocity u = (f + r)/m - reference satisfies the
// Signorini-Coulomb law (Eq. 8) in exactly one branch.
//
// A node with one contact is solved in closed form. Nodes with several contacts (pairs, or two
// obstacles) are coupled, and are solved by projected Gauss-Seidel sweeps: obstacle contacts
// first (in parallel over nodes), then the self-collision pairs layer by layer (in parallel
// within a layer, ContactLayering.h). The impulses are kept from one PD iteration to the next
// (the contact set is fixed during a step), so the sweeps continue where they stopped (Ly et
// al.'s warm start).
//
// Sweep convergence test: a sweep that changes no contact's impulse by more than `tolerance`
// (as a velocity, |delta r| / m, in m/s) ends the solve, as does the sweep cap. The outer PD
// residual (Simulator) measures what is left, since any change of r between PD iterations moves
// the next global solve.

#include <weft/record/ContactPoint.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>

#include <vector>

namespace weft {

class ContactSolver {
 public:
  explicit ContactSolver(int nodeCount) : slotOf_(nodeCount, -1) {}

  // Takes the step's contacts: obstacle contacts sorted by node, pairs in layer order with
  // `layerStart` boundaries. Resets all impulses to zero.
  //
  // `mass` is the lumped mass. `lawMass` (optional, per node) is the mass the law is solved with:
  // the law relates an impulse r and a velocity u through the free velocity w = u - r / m~, and
  // (r, u) satisfies Eq. 8 exactly when r = m~ L(w) for ANY m~ > 0 (per contact), so m~ changes
  // the iteration, never the solution (it is the augmentation parameter of Alart and Curnier's
  // formulation). The "pd" iteration uses the lumped mass (DiffCloth Eq. 12); the Newton solve
  // a larger one (Simulator::solveContactNewton). The caller's free momentum must then be
  // m~ v + (b - P x) / h. The record reports the lumped (reduced) mass either way, so that what
  // it holds (r, u and d = m u - r with the lumped m) reads as DiffCloth's convention.
  void setContacts(const std::vector<ContactPoint>& obstacleContacts,
                   const std::vector<ContactPoint>& pairs, const std::vector<int>& layerStart,
                   const Eigen::VectorXd& mass, const Eigen::VectorXd* lawMass = nullptr);
  bool empty() const { return contacts_.empty(); }
  int contactCount() const { return static_cast<int>(contacts_.size()); }

  // One contact solve: returns the sweeps done. `freeMomentum` is m x 3 (kg m/s).
  int solve(const NodeMatrix& freeMomentum, double tolerance, int maxSweeps);
  // rhs.row(node) += scale * (total contact impulse on node), for the contact nodes only.
  void addImpulses(double scale, NodeMatrix& rhs) const;
  double lastChange() const { return lastChange_; }

  // The step's record (branch, frame, impulse, velocity per contact) and the counts per branch.
  void record(StepContacts& out) const;
  // The branch of the node's first contact (None when it has none), for diagnostics.
  ContactBranch branchOfNode(int node) const;

  // Linearisation of the last solve, for the semismooth Newton contact solve (Simulator):
  // the impulses r(f) as a function of the free momentum f, differentiated in each contact's
  // branch (ContactLawJacobian.h). Coupled contacts (a node on two obstacles, self-collision
  // pairs sharing nodes) are differentiated through the fixed point their Gauss-Seidel sweeps
  // converge to, by the same sweeps linearised (addLawJacobian). Returns how many contacts
  // changed branch since the previous linearisation of the step.
  int linearize();
  // out += h dr/df q for q = h df (impulse-per-momentum blocks; out and q are m x 3).
  void addLawJacobian(const NodeMatrix& q, NodeMatrix& out) const;
  // The velocity directions each contact node's branches prescribe (stick: all three; slip: the
  // normal), as a projector per node: z.row(node) = C r.row(node) / m for contact nodes
  // (obstacle contacts only; pairs prescribe relative velocities and are left free).
  void pinnedVelocity(const NodeMatrix& r, NodeMatrix& z) const;
  // v.row(node) <- (I - C) v.row(node) for contact nodes.
  void removePinned(NodeMatrix& v) const;

 private:
  struct Slot {  // one node that has contacts
    int node;
    double mass;
    Vec3 freeVelocity;  // f / m
    Vec3 impulse;       // total contact impulse on the node
    Mat3 pinned;        // projector onto the prescribed velocity directions (linearize())
  };
  // A contact in the solve: its record (the detected frame, then the branch and impulse the
  // sweeps leave) and the solve's own state.
  struct Contact {
    ContactPoint point;    // point.effectiveMass: the lumped (reduced) mass, for the record
    int a = -1, b = -1;    // slots (b = -1 for an obstacle contact)
    double lawMass = 0.0;  // the law's (reduced) mass m~
    Mat3 law;              // d du / d w in the contact's branch (linearize())
    ContactBranch linearized = ContactBranch::None;  // the branch at the last linearize()
  };
  // A detected contact as the solve starts it: in take-off, no impulse, `recordMass` (the lumped
  // mass) for the record and `lawMass` (m~) for the law.
  static Contact started(const ContactPoint& detected, int a, int b, double lawMass,
                         double recordMass);
  Vec3 freeVelocity(const Contact& c) const;  // w: the contact's velocity without its own impulse
  double update(Contact& c);                  // one Gauss-Seidel update; returns |delta r| / m

  std::vector<int> slotOf_;  // per node
  std::vector<Slot> slots_;
  std::vector<Contact> contacts_;
  std::vector<int>
      groupStart_;  // obstacle contacts of one node: [groupStart_[g], groupStart_[g + 1])
  std::vector<int> layerStart_;  // pairs: contacts_[pairBegin_ + layerStart_[l] ...]
  int pairBegin_ = 0;
  bool coupled_ = false;  // some node has more than one contact
  double lastChange_ = 0.0;
  mutable std::vector<Vec3> linearImpulse_,
      linearTotal_;  // addLawJacobian's sweeps (per contact, slot)
  // Per group of obstacle contacts on one node (empty for a single contact): the 3k x 3 map from
  // the node's momentum to its k linearised impulses (linearize()).
  std::vector<Eigen::MatrixXd> groupResponse_;
};

}  // namespace weft
