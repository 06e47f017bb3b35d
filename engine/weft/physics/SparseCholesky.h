#pragma once
// CHOLMOD Cholesky factorisation of the PD system matrix, factorised once and reused for
// every global step until the matrix changes (DiffCloth Sec. 3.1: "P is a constant matrix that
// can be prefactorized"). CHOLMOD orders and factorises; the factor is then kept as a simplicial
// L L^T and the solves are our own loops over it with the three coordinates interleaved (for the
// small, many-times-solved systems of cloth this is about twice as fast as cholmod_solve2).
// No allocation per solve.

#include <weft/core/Types.h>

#include <Eigen/SparseCore>

#include <vector>

struct cholmod_common_struct;
struct cholmod_factor_struct;
struct cholmod_dense_struct;

namespace weft {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Factorises a symmetric positive definite matrix (only its lower triangle is read). The
  // symbolic analysis is kept while the sparsity pattern stays the same.
  // Returns false if the matrix is not positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& matrix);
  bool factorized() const { return factor_ != nullptr; }
  int size() const { return size_; }
  // From CHOLMOD's symbolic analysis of the current pattern (0 before the first factorize):
  // the floating-point operations of one numeric factorisation and the entries of L. They cost
  // a factorisation and a solve without timing anything, so choices made from them repeat
  // exactly.
  double factorFlops() const { return factorFlops_; }
  double factorEntries() const { return factorEntries_; }
  // Flops of factorising the 3m x 3m matrix with this m x m matrix's pattern in 3 x 3 blocks
  // (the clamped Hessian K+ of a cloth whose PD matrix P this factors) over the flops of one
  // iteration preconditioned by this factor (a 3-column solve and a product with a matrix of
  // `nonZeros` 3 x 3 blocks). Both the Newton contact solve and the adjoint's GMRES weigh a
  // factorisation of K+ against iterations with P by it.
  double blockFactorFlopRatio(double nonZeros) const {
    return 26.0 * factorFlops_ / (12.0 * factorEntries_ + 18.0 * nonZeros);
  }

  // b <- P^{-1} b, for an n x k column-major block (k right-hand sides solved together).
  void solveInPlace(double* data, int columns);
  void solveInPlace(NodeMatrix& b) { solveInPlace(b.data(), 3); }
  void solveInPlace(Eigen::VectorXd& b) { solveInPlace(b.data(), 1); }

 private:
  cholmod_common_struct* common_;
  cholmod_factor_struct* factor_ = nullptr;
  cholmod_factor_struct* symbolic_ = nullptr;  // cholmod_analyze's result, kept while the pattern is
  cholmod_dense_struct *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;
  template <int W>
  void solveBlock(double* data);
  const int* colStart_ = nullptr;
  const int* rowIndex_ = nullptr;
  const double* values_ = nullptr;
  const int* perm_ = nullptr;
  std::vector<double> work_;
  Eigen::SparseMatrix<double> lower_;  // kept: CHOLMOD views its arrays
  int size_ = 0;
  long long patternNonZeros_ = -1;
  double factorFlops_ = 0.0, factorEntries_ = 0.0;
};

}  // namespace weft
