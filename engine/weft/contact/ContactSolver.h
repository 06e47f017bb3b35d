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

#include <weft/contact/ContactConstraint.h>
#include <weft/contact/StepContacts.h>
#include <weft/physics/StepStats.h>

#include <vector>

namespace weft {

class ContactSolver {
 public:
  explicit ContactSolver(int nodeCount) : slotOf_(nodeCount, -1) {}

  // Takes the step's contacts: obstacle contacts sorted by node, pairs in layer order with
  // `layerStart` boundaries. Resets all impulses to zero.
  void setContacts(const std::vector<ContactConstraint>& obstacleContacts, const std::vector<ContactConstraint>& pairs,
                   const std::vector<int>& layerStart, const Eigen::VectorXd& mass);
  bool empty() const { return contacts_.empty(); }
  int contactCount() const { return static_cast<int>(contacts_.size()); }

  // One contact solve: returns the sweeps done. `freeMomentum` is m x 3 (kg m/s).
  int solve(const NodeMatrix& freeMomentum, double tolerance, int maxSweeps);
  // rhs.row(node) += scale * (total contact impulse on node), for the contact nodes only.
  void addImpulses(double scale, NodeMatrix& rhs) const;
  double lastChange() const { return lastChange_; }

  // The step's record (branch, frame, impulse, velocity per contact) and the counts per branch.
  void record(StepContacts& out) const;

 private:
  struct Slot {  // one node that has contacts
    int node;
    double mass;
    Vec3 freeVelocity;  // f / m
    Vec3 impulse;       // total contact impulse on the node
  };
  struct Contact {
    int a, b;  // slots (b = -1 for an obstacle contact)
    int obstacle;
    Vec3 normal, reference;
    double friction, effectiveMass;
    Vec3 impulse;  // on slot a (slot b receives the opposite)
    ContactBranch branch;
    Vec3 sample;  // detection's surface sample (recorded for the backward pass)
    double pathFraction;
  };
  double update(Contact& c);  // one Gauss-Seidel update; returns |delta r| / m

  std::vector<int> slotOf_;  // per node
  std::vector<Slot> slots_;
  std::vector<Contact> contacts_;
  std::vector<int> groupStart_;  // obstacle contacts of one node: [groupStart_[g], groupStart_[g + 1])
  std::vector<int> layerStart_;  // pairs: contacts_[pairBegin_ + layerStart_[l] ...]
  int pairBegin_ = 0;
  bool coupled_ = false;  // some node has more than one contact
  double lastChange_ = 0.0;
};

}  // namespace weft
