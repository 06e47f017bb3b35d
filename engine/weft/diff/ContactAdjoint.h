#pragma once
// The contact part of one backward step (DiffCloth Sec. 4.2, Eqs. 22-30; notes Sec. 3). A step
// with contact solves
//
//   G1 = M (x - s) + h^2 grad E(x) - E q = 0                       (the PD step, Eq. 9)
//   G2_c = q_c - h m_c L_c(w_c) = 0   for every contact c           (the law, Eq. 8)
//   w_c  = G_c M^-1 (f + E q / h) - q_c / (h m_c) - ref_c,   f = M v_n + h f_ext + h f_int(x)
//
// with q_c = h r_c the contact's impulse times h, E the map from contact impulses to nodes (+ on
// node a, - on the pair's node b), G_c = E_c^T the contact's relative velocity, m_c its effective
// mass and w_c its free velocity (the velocity it would have without its own impulse). The
// adjoint of this pair of equations, with D = blockdiag(m_c dL_c/dw), H = G M^-1 E and
// N = diag(1/m_c), is
//
//   K z + (K - M) wbar = g,   wbar = M^-1 G^T D^T y,   T^T y = G z,   T = I - D (H - N),
//
// i.e. (P - Delta P - Delta R)^T z = g with Delta R = R' (Delta P - C), R' = dr/df = E T^-1 D G
// M^-1 (DiffCloth Eq. 29, transposed: the slip blocks make it unsymmetric). T couples only
// contacts that share a node (a node touching two obstacles, pairs sharing a node); where none
// do, T = I and R' is one 3 x 3 block per contact node. Take-off contacts have D = 0 and drop out.
//
// The contact frame depends on the start of the step (DiffCloth Sec. 4.3, J_n(x_n, v_n)): the
// reference velocity holds the gap, gap = n . (x_n - c) - skin, and n, c and the surface velocity
// are functions of where detection sampled the surface, s = x_n + tau (predicted displacement)
// with d s / d v_n = tau h (the warm-start part of the prediction is treated as fixed). Pairs take
// n = (x_a - x_b)/|x_a - x_b| at x_n. The shape's dn/ds and dc/ds come from central differences of
// its own sample() (every shape, analytic or mesh, smooth or not, through one path); the law's
// derivatives are analytic (ContactLawJacobian.h).

#include <weft/contact/ContactObstacle.h>
#include <weft/diff/SceneParameter.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/Model.h>
#include <weft/record/StepContacts.h>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <memory>
#include <vector>

namespace weft {

class ContactAdjoint {
 public:
  // The model's obstacles, posed per step here. The model must outlive the adjoint.
  explicit ContactAdjoint(const Model& model);
  ~ContactAdjoint();

  // Prepares the step from x0 = x_n (time t0) to t1 from its contact record. Throws
  // NumericalError(step, "backward", ...) when the contacts sharing a node leave T singular
  // (e.g. one node stuck between two obstacles: its impulse split is not unique).
  void prepare(const StepContacts& contacts, const NodeMatrix& x0, double t0, double t1, int step);
  // Contacts with an impulse (stick or slip) in the prepared step.
  int size() const { return static_cast<int>(contacts_.size()); }
  // A contact that prescribes a velocity in the prepared step: a node's (an obstacle contact,
  // partner -1) or a self-collision pair's relative velocity v_node - v_partner (only where
  // neither node has another contact, so that the pair's block of S involves the two nodes
  // alone). The projector picks the prescribed directions, I where it sticks (or a node touches
  // two obstacles), n n^T where it slips; s is the block of S = I + R'^T (z + wbar = S z) acting
  // on the prescribed velocity, I + dL/dw^T of the contact, zero along those directions. A pair's
  // S keeps its nodes' mass-weighted mean velocity and maps their relative velocity by s, as an
  // obstacle's maps the node's. AdjointSystem::precondition inverts them exactly.
  struct PinnedContact {
    int node = -1;
    int partner = -1;
    Mat3 projector;
    Mat3 s;  // (of a node with two obstacle contacts: zero, as the projector is I)
    Vec3 normal;
  };
  const std::vector<PinnedContact>& pinnedContacts() const { return pinned_; }
  bool coupled() const { return coupled_; }

  // wbar = R'^T z (m x 3) and the contact-space adjoint y = T^-T G z (size() x 3).
  void applyTransposed(const NodeMatrix& z, NodeMatrix& wbar, Eigen::MatrixX3d& y) const;

  // The blocks of the augmented transposed system for a direct solve,
  //   [ K   (K - M) B ] [z]   [g]
  //   [-G   T^T       ] [y] = [0],     B = M^-1 G^T D^T,
  // as triplets: B (3m x 3c), -G (3c x 3m) and T^T (3c x 3c), with node-space index
  // coordinate * m + node and contact-space index 3 * contact + coordinate.
  void appendTransposedBlocks(std::vector<Eigen::Triplet<double>>& b,
                              std::vector<Eigen::Triplet<double>>& minusG,
                              std::vector<Eigen::Triplet<double>>& tTransposed) const;

  // dL/dx_n and dL/dv_n through the contact frames (gap, normal, surface velocity) given y.
  void addStateGradients(const Eigen::MatrixX3d& y, NodeMatrix& dLdx0, NodeMatrix& dLdv0) const;
  // The contact's share of the parameter gradients given y and wbar: friction of an obstacle or
  // of self-collision (the slip branch's dL/dmu), and density through the law's masses. The
  // force-like parameters (stiffness, external forces, handles) need nothing here: their partials
  // are ParameterPartials' with S^T z = z + wbar in place of z (notes Sec. 3.4), which is what the
  // caller hands it; density's inertia term is corrected for that here.
  void addParameterGradients(const std::vector<SceneParameter>& parameters,
                             const Eigen::MatrixX3d& y, const NodeMatrix& wbar,
                             const NodeMatrix& x0, const NodeMatrix& v0, const NodeMatrix& x1,
                             Eigen::VectorXd& gradient) const;

 private:
  // A recorded contact (its ContactPoint: nodes, obstacle, branch, normal, friction and
  // effective mass m_c) and the law's derivatives at it.
  struct Contact {
    ContactPoint point;
    Mat3 d;               // m_c dL/dw
    Mat3 frameX;          // d (h r_c) / d x_n of node a (node b of a pair: minus this)
    Mat3 frameV;          // d (h r_c) / d v_n of node a (obstacle contacts)
    Vec3 frictionRate;    // d (h r_c) / d mu_c
    Vec3 velocityChange;  // the law's du = r_c / m_c
  };
  void frameOfObstacleContact(const ContactPoint& p, const NodeMatrix& x0, const Mat3& lawNormal,
                              Contact& c) const;
  void frameOfPair(const ContactPoint& p, const NodeMatrix& x0, const Mat3& lawNormal,
                   Contact& c) const;

  const Scene& scene_;
  const ClothModel& model_;
  double h_;
  std::vector<ContactObstacle> obstacles_;
  std::vector<Contact> contacts_;
  // Added to the diagonal of T^T's singular groups (contacts sticking around one node): T's other
  // entries are O(1) (the law's m_c dL/dw over a node mass), so this moves the solution by about
  // 1e-9 relative outside the split's null space.
  static constexpr double kSingularCouplingShift = 1e-9;  // the error message quotes it
  // A group of coupled contacts is singular when its block of T^T has a singular value below
  // this fraction of its largest: exact zeros come out of rounding at about 1e-16, while
  // genuinely ill-conditioned slip pairs lie orders of magnitude above and are left exact.
  static constexpr double kSingularCouplingRatio = 1e-12;
  std::vector<PinnedContact> pinned_;
  std::vector<int> pinnedSlot_;  // node -> index in pinned_ or -1 (reset after each prepare)
  std::vector<int> touching_;    // node -> contacts on it in the prepared step
  bool coupled_ = false;
  Eigen::SparseMatrix<double> tTransposed_;  // when coupled
  Eigen::SparseLU<Eigen::SparseMatrix<double>> tSolver_;
  mutable Eigen::VectorXd work_;
};

}  // namespace weft
