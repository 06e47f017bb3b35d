#pragma once
// The linear system of one backward step (DiffCloth Eq. 19, and Eq. 29 with contact):
//
//   K z = g,   K = P - Delta P                       (no contact in the step)
//   K z = g,   K = (P - Delta P - Delta R)^T         (contact: ContactAdjoint.h)
//
// with P = M + h^2 sum_i w_i A_i^T A_i the prefactorised PD matrix (Eq. 7, one coordinate,
// times I_3) and Delta P = h^2 sum_i w_i A_i^T (dp_i/dx)|_{x_{n+1}} the exact projection
// derivatives at the recorded end-of-step state x_{n+1}. P - Delta P is h^2 times the Hessian of
// the implicit-Euler energy (Eq. 3), hence symmetric; it is indefinite where the cloth is
// compressed (buckling modes). Delta R (the contact branches) makes K unsymmetric; with
// R'^T from ContactAdjoint, K z = (P - Delta P)(z + R'^T z) - M R'^T z.
//
// The constraints are instances of the model's families, as the Simulator's are, so P and
// Delta P are exactly the forward's. Vectors are m x 3
// NodeMatrix blocks; the flat 3m ordering used by the assembled matrix is the NodeMatrix's
// column-major storage (index = coordinate * m + node).

#include <weft/core/Types.h>
#include <weft/diff/ContactAdjoint.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/HessianAssembly.h>
#include <weft/physics/Model.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/SparseCholesky.h>

#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace weft {

class AdjointSystem {
 public:
  // Instantiates the model's constraints and factorises P; keeps the model. Throws
  // NumericalError if P is not positive definite.
  explicit AdjointSystem(std::shared_ptr<const Model> model);
  ~AdjointSystem();

  const ClothModel& cloth() const { return model_; }
  double dt() const { return h_; }
  int nodeCount() const { return model_.nodeCount(); }
  const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints() const {
    return constraints_;
  }
  const Eigen::SparseMatrix<double>& systemMatrix() const { return system_; }  // P, one coordinate

  // Evaluates the projection derivatives (Delta P) at x (the recorded x_{n+1}) and takes the
  // step's prepared contacts (null or empty: none). `contact` must outlive the step's solve.
  void prepare(const NodeMatrix& x, const ContactAdjoint* contact = nullptr);
  bool dependsOnStart() const { return dependsOnStart_; }
  // out += h^2 sum_i (dp_i/dx_n)^T w_i A_i q: what the step equations' x_n dependence through
  // such projections passes back to dL/dx_n (q = S^T z, as for force-like parameters).
  void addStartGradient(const NodeMatrix& start, const NodeMatrix& q, NodeMatrix& out) const;
  bool hasDeltaP() const { return anyDerivative_; }
  bool hasContact() const { return contact_ != nullptr; }
  // K != P: the fixed point of Eq. 20/30 needs more than one solve.
  bool hasCoupling() const { return anyDerivative_ || contact_ != nullptr; }

  void multiplyP(const NodeMatrix& in, NodeMatrix& out) const;       // out = P in
  void multiplyDeltaP(const NodeMatrix& in, NodeMatrix& out) const;  // out = Delta P in
  void multiplyK(const NodeMatrix& in, NodeMatrix& out) const;       // out = K in
  void multiplyCoupling(const NodeMatrix& in, NodeMatrix& out)
      const;                       // out = (P - K) in (Eq. 30's (Delta P + Delta R)^T)
  void solveP(NodeMatrix& inOut);  // inOut = P^{-1} inOut (CHOLMOD factor)
  // GMRES's right preconditioner: inOut = B inOut with B ~ K^-1, built on P's factor or (hessian)
  // the clamped Hessian's, F. Without contact B is F's solve. With contact, K z =
  // K_e S z + M (I - S) z (K_e = P - Delta P, z + wbar = S z), and on a node an obstacle pins
  // S is zero along the prescribed directions Pi (ContactAdjoint::PinnedContact: all of a sticking
  // node's, a slipping node's normal), where K's columns are M alone, and on a slipping node's
  // tangent plane S is I - g (I - t t^T) (friction's gain g < 1). Splitting z = u + c with
  // Pi u = 0 and Pi c = c: K z = K_e S u + M (I - S) u + M c. The free part takes w = S u from
  // (I - Pi) F^-1 (I - Pi) g and u = Q w with Q S's inverse on the tangent plane (a direction
  // where 1 - g < m / P_ii is pinned instead: there S ~ 0 and K's column is nearly M's); the
  // pinned part is then exact, c = M^-1 Pi (g - K u). F's solve alone models the columns M Pi as
  // P's, larger by h^2 times the node's stiffness, which slows GMRES on contact steps and sends
  // slowly slipping ones to the LU fallback (docs/benchmarks.md, "Contact-pinned velocities in
  // the preconditioner"). One more product
  // with K per application; the forward's Newton contact solve preconditions its Jacobian, the
  // transpose of this K, the same way (Simulator::preconditionContact), for obstacles only.
  // A self-collision pair whose nodes have no other contact is the same in its relative velocity:
  // S keeps the mass-weighted mean (m_a z_a + m_b z_b) / (m_a + m_b) and maps r = z_a - z_b by
  // the pair's block (m_c = the pair's effective mass for m), so Pi and Q act on r, the pinned
  // columns z = (e / m_a, -e / m_b) give K z = (e, -e), and the correction takes half the
  // residual's difference, e = Pi (res_a - res_b) / 2.
  void precondition(NodeMatrix& inOut, bool hessian);
  // Tests and benchmarks: false makes precondition() the factor's solve also with contact.
  void setContactPreconditioning(bool on) { contactPreconditioning_ = on; }
  // A preconditioner closer to K than P (solver.backward.preconditioner "hessian"): H = P minus
  // Delta P with every projection derivative clamped as the Newton forward clamps it
  // (prepareDerivative(x, true)), i.e. h^2 times the implicit-Euler Hessian with each element's
  // indefinite part removed: symmetric positive definite (M > 0), equal to K wherever no element
  // is compressed. P keeps the transverse and rotational stiffness that Delta P takes away from a
  // cloth in tension, which is why GMRES preconditioned by P needs many iterations per step on
  // Wind and H a handful (docs/benchmarks.md).
  // factorClampedHessian assembles H at the prepared state (as assembleK) and
  // factorises it with CHOLMOD (3m x 3m, symbolic analysis kept); false if that fails.
  bool factorClampedHessian();
  void solveClampedHessian(NodeMatrix& inOut);  // inOut = H^{-1} inOut
  // K assembled as a 3m x 3m sparse matrix (flat index = coordinate * m + node) from the
  // constraints' element blocks of Delta P (HessianAssembly).
  Eigen::SparseMatrix<double> assembleK() const;
  // The system for a direct solve: P - Delta P without contact; with contact the augmented
  // transposed system of ContactAdjoint::appendTransposedBlocks, (3m + 3c) square, whose first 3m
  // unknowns are z for a right-hand side [g; 0].
  Eigen::SparseMatrix<double> assembleSystem() const;
  // What one factorClampedHessian costs, in GMRES iterations preconditioned by P, estimated from
  // operation counts so that choices made from it repeat exactly: kFactorCostScale times the
  // square root of the flop ratio of H's factorisation over an iteration's (H has P's pattern in
  // 3 x 3 blocks, so its flops are about 26 times P's factor's; an iteration is a P solve of 12
  // flops and a K product of about 18 flops per stored entry). Not proportional to the flop
  // ratio: the larger the matrix, the larger CHOLMOD's supernodes and the faster its BLAS runs
  // per flop. kFactorCostScale is fitted to `weft bench backward --calibrate`
  // (docs/benchmarks.md, "The clamped Hessian from element blocks").
  double hessianFactorCost() const;
  // H's factorisation flops over an iteration's (SparseCholesky::blockFactorFlopRatio).
  double hessianFlopRatio() const;
  // What one GMRES iteration preconditioned by H costs, in iterations preconditioned by P, from
  // operation counts: a one-column solve with H's factor (4 flops per entry of its L; before H's
  // first analysis 9 times P's entries, H having P's pattern in 3 x 3 blocks) and a product with
  // K (18 flops per stored entry of P), over a three-column solve with P's factor (12 flops per
  // entry) and the same product. `weft bench backward --calibrate` prints it beside the timed
  // ratio.
  double hessianIterationCost() const;
  static constexpr double kFactorCostScale = 15.0;

 private:
  std::shared_ptr<const Model> compiled_;
  const ClothModel& model_;
  double h_;
  std::vector<std::unique_ptr<ProjectiveConstraint>> constraints_;
  Eigen::SparseMatrix<double> system_;
  SparseCholesky cholesky_;
  SparseCholesky hessianCholesky_{SparseCholesky::Use::Preconditioner};
  NodeMatrix preparedX_;
  bool anyDerivative_ = false;
  bool dependsOnStart_ = false;
  mutable std::vector<NodeMatrix> rows_;  // per-constraint derivative rows (work buffers)
  const ContactAdjoint* contact_ = nullptr;
  bool contactPreconditioning_ = true;
  // precondition()'s blocks per pinned contact (prepare()): the directions it pins, Pi, and the
  // map Q from the factor's solution to z on the others (S's inverse there), both acting on the
  // node's velocity or on the pair's relative one.
  struct PinnedBlock {
    int node, partner;  // (partner -1: an obstacle contact)
    Mat3 pinned, freeMap;
    double alpha, beta;  // a pair's z_a = c + alpha r, z_b = c - beta r (an obstacle's: 1, 0)
    double mass;         // m_c (an obstacle's: the node's mass)
  };
  std::vector<PinnedBlock> pinnedBlocks_;
  NodeMatrix preconditionRhs_, preconditionProduct_;
  void multiplyElastic(const NodeMatrix& in, NodeMatrix& out) const;  // out = (P - Delta P) in
  mutable NodeMatrix contactWbar_, contactSum_, work_;
  mutable Eigen::MatrixX3d contactY_;
  mutable std::unique_ptr<HessianAssembly> assembly_;  // assembleK's pattern and positions
  Eigen::SparseMatrix<double> clamped_;  // H, assembled in place by factorClampedHessian
};

}  // namespace weft
