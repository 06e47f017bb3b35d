#pragma once
// A family of Projective Dynamics constraints of one kind (all stretch triangles, all bending
// hinges, ...). Each row r of the family has energy  W_r = w_r/2 |A_r x - p_r(x)|^2
// (DiffCloth Eq. 4), where A_r is a scalar row acting identically on x, y and z, so the
// family's contribution to the system matrix is  h^2 A^T W A  on one coordinate (Eq. 7) and
// the full matrix is that block times I_3. Instances are stored structure-of-arrays and
// projected in parallel without allocation.

#include <weft/core/Types.h>

#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace weft {

class ProjectiveConstraint {
 public:
  virtual ~ProjectiveConstraint() = default;
  virtual const char* name() const = 0;

  int rowCount() const { return static_cast<int>(weights_.size()); }
  const Eigen::VectorXd& weights() const { return weights_; }
  // A^T (nodes x rows), unweighted, for gathering projections into the global right-hand side.
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& selectionTransposed() const { return at_; }
  // sum_r w_r A_r^T A_r, one coordinate (nodes x nodes).
  Eigen::SparseMatrix<double> weightedGram() const;

  // Called once per time step, before the iterations, with the end-of-step time.
  virtual void beginStep(double /*time*/) {}
  // Local step: writes w_r * p_r(x) into row r of `weightedProjections` (rows x 3) and returns
  // the family's energy sum_r W_r(x).
  virtual double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const = 0;

 protected:
  // Builds A^T from (row, node, coefficient) triplets once the rows are known.
  void setSelection(int nodes, const std::vector<Eigen::Triplet<double>>& rowNodeCoefficients);
  Eigen::VectorXd weights_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> at_;
};

}  // namespace weft
