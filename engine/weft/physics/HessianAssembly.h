#pragma once
// Assembles K = P (x) I_3 - h^2 Delta P, the matrix of the Newton contact solve and of the
// adjoint (DiffCloth Sec. 4.1, Eq. 19), from the constraint families' element blocks
// (ProjectiveConstraint::derivativeBlocks) straight into a fixed 3m x 3m pattern: the values
// start from P's and each element's block is scattered into precomputed positions, with no
// sort and no allocation after construction. With the derivatives prepared `definite` this is
// the clamped Hessian K+ that preconditions both solves.
//
// Flat index = coordinate * m + node, the column-major storage of a NodeMatrix, so a NodeMatrix's
// data is the 3m vector the matrix multiplies and its factor solves. Every entry of P's block
// pattern is stored, zeros included, so the pattern (and a kept symbolic factorisation) never
// changes between assemblies.

#include <weft/physics/ProjectiveConstraint.h>

#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace weft {

class HessianAssembly final : private DerivativeBlockSink {
 public:
  // `system`: P (m x m, one coordinate), whose pattern contains every element's node pairs.
  explicit HessianAssembly(const Eigen::SparseMatrix<double>& system);

  // out = P (x) I_3 + scale * (the families' prepared derivative blocks): scale = -h^2 gives K.
  // Every family with a derivative must offer its blocks (std::logic_error otherwise). `out` is
  // either a matrix this assembly produced, whose values are then overwritten in place (its
  // pattern is taken to be ours when its size and entry count are), or anything else, replaced.
  void assemble(const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints, double scale,
                Eigen::SparseMatrix<double>& out);

 private:
  void add(const int* nodes, int count, const double* block) override;
  // Position in the value array of row (coordinate 0, node i) within column (coordinate e, node
  // j); coordinate d of the row adds d * degree(j).
  int position(int i, int j, int e) const;

  int m_ = 0;
  std::vector<int> neighbourStart_, neighbours_;  // per node, sorted, itself included
  Eigen::SparseMatrix<double> pattern_;           // 3m x 3m, values = P (x) I_3
  double* values_ = nullptr;                      // the matrix being assembled
  double scale_ = 0.0;
};

}  // namespace weft
