#include <weft/physics/SparseCholesky.h>

#include <cholmod.h>

#include <cstdlib>
#include <cstring>

namespace weft {

SparseCholesky::SparseCholesky() : common_(new cholmod_common) {
  cholmod_start(common_);
  common_->print = 0;
  common_->error_handler = nullptr;
}

SparseCholesky::~SparseCholesky() {
  if (factor_) cholmod_free_factor(&factor_, common_);
  if (symbolic_) cholmod_free_factor(&symbolic_, common_);
  if (x_) cholmod_free_dense(&x_, common_);
  if (y_) cholmod_free_dense(&y_, common_);
  if (e_) cholmod_free_dense(&e_, common_);
  cholmod_finish(common_);
  delete common_;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& matrix) {
  lower_ = matrix.triangularView<Eigen::Lower>();
  lower_.makeCompressed();
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<size_t>(lower_.rows());
  view.nzmax = static_cast<size_t>(lower_.nonZeros());
  view.p = lower_.outerIndexPtr();
  view.i = lower_.innerIndexPtr();
  view.x = lower_.valuePtr();
  view.stype = -1;  // symmetric, lower triangle stored
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  const bool samePattern = symbolic_ && size_ == lower_.rows() && patternNonZeros_ == lower_.nonZeros();
  if (!samePattern) {
    if (symbolic_) cholmod_free_factor(&symbolic_, common_);
    symbolic_ = cholmod_analyze(&view, common_);
    factorFlops_ = common_->fl;
    factorEntries_ = common_->lnz;
    size_ = static_cast<int>(lower_.rows());
    patternNonZeros_ = lower_.nonZeros();
  }
  if (factor_) cholmod_free_factor(&factor_, common_);
  if (!symbolic_) return false;
  // The numeric factorisation starts from a copy of the symbolic analysis each time: the factor
  // below is converted to simplicial form for our solves, and refactorising that one would lose
  // CHOLMOD's supernodal (BLAS) path (10x slower for the adjoint's per-step 3m x 3m factor).
  factor_ = cholmod_copy_factor(symbolic_, common_);
  if (!factor_) return false;
  cholmod_factorize(&view, factor_, common_);
  if (common_->status == CHOLMOD_NOT_POSDEF || common_->status < CHOLMOD_OK) {
    cholmod_free_factor(&factor_, common_);
    return false;
  }
  // Our own triangular solves read L as a simplicial, packed L L^T factor. Converting once per
  // factorisation is cheap next to the thousands of solves that reuse it.
  if (!cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/1, /*to_super=*/0, /*to_packed=*/1,
                             /*to_monotonic=*/1, factor_, common_)) {
    cholmod_free_factor(&factor_, common_);
    return false;
  }
  colStart_ = static_cast<const int*>(factor_->p);
  rowIndex_ = static_cast<const int*>(factor_->i);
  values_ = static_cast<const double*>(factor_->x);
  perm_ = static_cast<const int*>(factor_->Perm);
  work_.resize(3 * static_cast<std::size_t>(size_));
  return true;
}

template <int W>
void SparseCholesky::solveBlock(double* data) {
  // x = P^T L^{-T} L^{-1} P b with the W right-hand sides interleaved, so each nonzero of L
  // updates W contiguous values.
  const int n = size_;
  const std::size_t stride = static_cast<std::size_t>(n);
  double* z = work_.data();
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < W; ++c) z[W * k + c] = data[c * stride + perm_[k]];
  for (int j = 0; j < n; ++j) {  // L z' = z (column-oriented; the diagonal comes first)
    const int begin = colStart_[j], end = colStart_[j + 1];
    double zj[W];
    for (int c = 0; c < W; ++c) zj[c] = z[W * j + c] /= values_[begin];
    for (int k = begin + 1; k < end; ++k) {
      const double l = values_[k];
      double* zi = z + W * rowIndex_[k];
      for (int c = 0; c < W; ++c) zi[c] -= l * zj[c];
    }
  }
  for (int j = n - 1; j >= 0; --j) {  // L^T z'' = z'
    const int begin = colStart_[j], end = colStart_[j + 1];
    double acc[W];
    for (int c = 0; c < W; ++c) acc[c] = z[W * j + c];
    for (int k = begin + 1; k < end; ++k) {
      const double l = values_[k];
      const double* zi = z + W * rowIndex_[k];
      for (int c = 0; c < W; ++c) acc[c] -= l * zi[c];
    }
    for (int c = 0; c < W; ++c) z[W * j + c] = acc[c] / values_[begin];
  }
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < W; ++c) data[c * stride + perm_[k]] = z[W * k + c];
}

void SparseCholesky::solveInPlace(double* data, int columns) {
  if (columns == 3) return solveBlock<3>(data);
  if (columns == 1) return solveBlock<1>(data);
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(size_);
  b.ncol = static_cast<size_t>(columns);
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = data;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_solve2(CHOLMOD_A, factor_, &b, nullptr, &x_, nullptr, &y_, &e_, common_);
  std::memcpy(data, x_->x, sizeof(double) * b.nzmax);
}

}  // namespace weft
