#include <weft/physics/SparseCholesky.h>

#include <cholmod.h>

#include <cstring>

namespace weft {

SparseCholesky::SparseCholesky() : common_(new cholmod_common) {
  cholmod_start(common_);
  common_->print = 0;
  common_->error_handler = nullptr;
}

SparseCholesky::~SparseCholesky() {
  if (factor_) cholmod_free_factor(&factor_, common_);
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
  const bool samePattern = factor_ && size_ == lower_.rows() && patternNonZeros_ == lower_.nonZeros();
  if (!samePattern) {
    if (factor_) cholmod_free_factor(&factor_, common_);
    factor_ = cholmod_analyze(&view, common_);
    size_ = static_cast<int>(lower_.rows());
    patternNonZeros_ = lower_.nonZeros();
  }
  if (!factor_) return false;
  cholmod_factorize(&view, factor_, common_);
  if (common_->status == CHOLMOD_NOT_POSDEF || common_->status < CHOLMOD_OK) {
    cholmod_free_factor(&factor_, common_);
    return false;
  }
  return true;
}

void SparseCholesky::solveInPlace(double* data, int columns) {
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
