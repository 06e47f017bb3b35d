#pragma once
// A family of Projective Dynamics constraints of one kind (all stretch triangles, all bending
// hinges, ...). Each row r of the family has energy  W_r = w_r/2 |A_r x - p_r(x)|^2
// (DiffCloth Eq. 4), where A_r is a scalar row acting identically on x, y and z, so the
// family's contribution to the system matrix is  h^2 A^T W A  on one coordinate (Eq. 7) and
// the full matrix is that block times I_3. Instances are stored structure-of-arrays and
// projected in parallel without allocation.

#include <weft/core/Types.h>

#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace weft {

// Receives a constraint family's derivative element by element (ProjectiveConstraint::
// derivativeBlocks): `block` is the (3 count) x (3 count) column-major matrix
// sum_r w_r A_r^T D_r A_r over the element's rows, restricted to its `count` nodes, entry
// (3 a + d, 3 b + e) coupling coordinate d of nodes[a] with coordinate e of nodes[b].
class DerivativeBlockSink {
 public:
  virtual ~DerivativeBlockSink() = default;
  virtual void add(const int* nodes, int count, const double* block) = 0;
};

class ProjectiveConstraint {
 public:
  virtual ~ProjectiveConstraint() = default;
  virtual const char* name() const = 0;
  // A copy with its own per-step state (Model::instantiateConstraints).
  virtual std::unique_ptr<ProjectiveConstraint> clone() const = 0;

  int rowCount() const { return static_cast<int>(weights_.size()); }
  const Eigen::VectorXd& weights() const { return weights_; }
  // A^T (nodes x rows), unweighted, for gathering projections into the global right-hand side.
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& selectionTransposed() const { return at_; }
  // out += scale * A^T weightedProjections: the constraint's share of the global right-hand
  // side (Eq. 7). Row-parallel, no allocation.
  void gather(const NodeMatrix& weightedProjections, double scale, NodeMatrix& out) const;
  // sum_r w_r A_r^T A_r, one coordinate (nodes x nodes).
  Eigen::SparseMatrix<double> weightedGram() const;

  // True when every projection is identically zero (e.g. bending of a flat rest mesh): the
  // family then only shapes P and needs no local step and no gather.
  virtual bool projectsToZero() const { return false; }
  // The family's energy sum_r W_r(x) without writing projections (for projectsToZero families).
  virtual double energy(const NodeMatrix& x) const;
  // Derivative of the projections, dp_r/dx = D_r A_r (DiffCloth Sec. 4.1: the blocks of Delta P).
  // prepareDerivative caches what D needs at x; with `definite` the derivative is clamped so
  // that A^T W (A - D A) is positive semi-definite (a descent direction for Newton), without it
  // it is exact (for the adjoint). applyDerivative writes w_r D_r(A_r dx) into row r.
  virtual bool hasDerivative() const { return false; }
  virtual void prepareDerivative(const NodeMatrix& /*x*/, bool /*definite*/) {}
  virtual void applyDerivative(const NodeMatrix& /*dx*/, NodeMatrix& /*weightedRows*/) const {}
  // The same prepared derivative as dense element blocks, for assembling Delta P directly
  // (HessianAssembly) instead of through products; false when the family has none.
  virtual bool derivativeBlocks(DerivativeBlockSink& /*sink*/) const { return false; }
  // Called once per time step, before the iterations, with the end-of-step time and the
  // positions the step starts from (x_n).
  virtual void beginStep(double /*time*/, const NodeMatrix& /*start*/) {}
  // Projections that depend on the step's start x_n (set by beginStep, constant in the step):
  // out += scale sum_r (dp_r/dx_n)^T w_r A_r q, the step equations' x_n term the adjoint carries
  // back (Backpropagation). None by default.
  virtual bool dependsOnStart() const { return false; }
  virtual void addStartGradient(const NodeMatrix& /*start*/, const NodeMatrix& /*q*/,
                                double /*scale*/, NodeMatrix& /*out*/) const {}
  // Local step: writes w_r * p_r(x) into row r of `weightedProjections` (rows x 3) and returns
  // the family's energy sum_r W_r(x).
  virtual double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const = 0;

 protected:
  // Builds A^T from (row, node, coefficient) triplets once the rows are known.
  void setSelection(int nodes, const std::vector<Eigen::Triplet<double>>& rowNodeCoefficients);
  Eigen::VectorXd weights_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> at_;
};

// The one-coordinate PD system matrix M + h^2 sum_i w_i A_i^T A_i (DiffCloth Eq. 7), compressed:
// the Simulator's P and the adjoint's (DiffCloth Sec. 4.1).
Eigen::SparseMatrix<double> assembleSystemMatrix(
    const Eigen::VectorXd& mass,
    const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints, double h);

}  // namespace weft
