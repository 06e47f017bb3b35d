#include <weft/physics/SparseCholesky.h>

#include <cholmod.h>
#include <omp.h>

#include <cstdlib>
#include <cstring>

namespace weft {

SparseCholesky::SparseCholesky(Use use) : use_(use), common_(new cholmod_common) {
  cholmod_start(common_);
  common_->print = 0;
  common_->error_handler = nullptr;
  if (use_ == Use::Preconditioner) {
    // Of AMD and nested dissection, CHOLMOD keeps the ordering with the fewer entries in L; on
    // cloth grids that is nested dissection (Slope K+ at 48^2: 0.94 against 1.02 million
    // entries, 0.185 against 0.227 GFlop; at 96^2 5.3 against 6.3 million, 1.76 against 2.64
    // GFlop). CHOLMOD also chooses supernodal or simplicial by flops per entry of L (its default
    // switch, 40): the sparse K+ of a cloth without bending factorises in small supernodes,
    // where the BLAS calls cost more than they save, and then takes the simplicial path below.
    common_->nmethods = 2;
    common_->method[0].ordering = CHOLMOD_AMD;
    common_->method[1].ordering = CHOLMOD_NESDIS;
  }
}

namespace {

// CHOLMOD 3 (SuiteSparse 5) runs the scatter and clearing loops of its supernodal factorisation
// on CHOLMOD_OMP_NUM_THREADS (4) OpenMP threads whatever the caller's budget. Under a smaller
// budget (a one-thread run, the 2-core CI machine) they run serially: the extra threads only
// contend for the cores (docs/how-it-works/forward.md, "Measured on the way").
class OpenMpBudget {
 public:
  OpenMpBudget()
      : levels_(omp_get_max_active_levels()),
        serial_(omp_get_max_threads() < CHOLMOD_OMP_NUM_THREADS) {
    if (serial_) omp_set_max_active_levels(0);
  }
  ~OpenMpBudget() {
    if (serial_) omp_set_max_active_levels(levels_);
  }
  OpenMpBudget(const OpenMpBudget&) = delete;
  OpenMpBudget& operator=(const OpenMpBudget&) = delete;

 private:
  int levels_;
  bool serial_;
};

// CHOLMOD's view of a compressed lower triangle (no copy): a symmetric matrix to analyse or
// factorise.
cholmod_sparse lowerTriangleView(Eigen::SparseMatrix<double>& lower) {
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<size_t>(lower.rows());
  view.nzmax = static_cast<size_t>(lower.nonZeros());
  view.p = lower.outerIndexPtr();
  view.i = lower.innerIndexPtr();
  view.x = lower.valuePtr();
  view.stype = -1;  // symmetric, lower triangle stored
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

}  // namespace

void SparseCholesky::orderByNodes(const Eigen::SparseMatrix<double>& nodeGraph) {
  Eigen::SparseMatrix<double> lower = nodeGraph.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  cholmod_sparse view = lowerTriangleView(lower);
  cholmod_factor* analysis = cholmod_analyze(&view, common_);
  if (!analysis) return;
  const int* order = static_cast<const int*>(analysis->Perm);
  nodeOrder_.assign(order, order + lower.rows());
  cholmod_free_factor(&analysis, common_);
  patternNonZeros_ = -1;  // analyse anew with it
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
  factorized_ = packed_ = false;
  lower_ = matrix.triangularView<Eigen::Lower>();
  lower_.makeCompressed();
  cholmod_sparse view = lowerTriangleView(lower_);
  const bool samePattern =
      symbolic_ && size_ == lower_.rows() && patternNonZeros_ == lower_.nonZeros();
  if (!samePattern) {
    if (symbolic_) cholmod_free_factor(&symbolic_, common_);
    const int nodes = static_cast<int>(nodeOrder_.size());
    if (nodes > 0 && lower_.rows() % nodes == 0) {
      // Node order[k]'s unknowns d m + order[k], d < blocks, consecutive (orderByNodes).
      const int blocks = static_cast<int>(lower_.rows()) / nodes;
      std::vector<int> given(static_cast<std::size_t>(lower_.rows()));
      for (int k = 0; k < nodes; ++k)
        for (int d = 0; d < blocks; ++d) given[blocks * k + d] = d * nodes + nodeOrder_[k];
      const int methods = common_->nmethods, ordering = common_->method[0].ordering;
      common_->nmethods = 1;
      common_->method[0].ordering = CHOLMOD_GIVEN;
      symbolic_ = cholmod_analyze_p(&view, given.data(), nullptr, 0, common_);
      common_->nmethods = methods;
      common_->method[0].ordering = ordering;
    } else {
      symbolic_ = cholmod_analyze(&view, common_);
    }
    factorFlops_ = common_->fl;
    factorEntries_ = common_->lnz;
    size_ = static_cast<int>(lower_.rows());
    patternNonZeros_ = lower_.nonZeros();
  }
  if (factor_) cholmod_free_factor(&factor_, common_);
  if (!symbolic_) return false;
  // The numeric factorisation starts from a copy of the symbolic analysis each time: the factor
  // is converted or packed for our solves, and refactorising a simplicial one would lose
  // CHOLMOD's supernodal (BLAS) path (10x slower for the adjoint's per-step 3m x 3m factor).
  factor_ = cholmod_copy_factor(symbolic_, common_);
  if (!factor_) return false;
  {
    const OpenMpBudget budget;
    cholmod_factorize(&view, factor_, common_);
  }
  if (common_->status == CHOLMOD_NOT_POSDEF || common_->status < CHOLMOD_OK) {
    cholmod_free_factor(&factor_, common_);
    return false;
  }
  perm_.assign(static_cast<const int*>(factor_->Perm),
               static_cast<const int*>(factor_->Perm) + size_);
  work_.resize(3 * static_cast<std::size_t>(size_));
  if (use_ == Use::Preconditioner && factor_->is_super) {
    // Single precision once L (in double) would outgrow a typical last-level cache.
    constexpr double kSinglePrecisionAboveBytes = 16e6;
    if (8.0 * static_cast<double>(factor_->xsize) > kSinglePrecisionAboveBytes) {
      packSupernodal(panelsSingle_);
      std::vector<double>().swap(panels_);
    } else {
      packSupernodal(panels_);
      std::vector<float>().swap(panelsSingle_);
    }
    packed_ = true;
    cholmod_free_factor(&factor_, common_);  // the panels are all the solves read
  } else {
    // Our own triangular solves read L as a simplicial, packed L L^T factor. Converting once per
    // factorisation is cheap next to the thousands of solves that reuse it.
    // (A simplicial factorisation is L D L^T, which exists for some indefinite matrices too; the
    // conversion meets a non-positive D and marks the factor, so the check is after it.)
    if (!cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/1, /*to_super=*/0, /*to_packed=*/1,
                               /*to_monotonic=*/1, factor_, common_) ||
        common_->status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n) {
      cholmod_free_factor(&factor_, common_);
      return false;
    }
    colStart_ = static_cast<const int*>(factor_->p);
    rowIndex_ = static_cast<const int*>(factor_->i);
    values_ = static_cast<const double*>(factor_->x);
  }
  factorized_ = true;
  return true;
}

template <class T>
void SparseCholesky::packSupernodal(std::vector<T>& panels) {
  // CHOLMOD keeps supernode s as a column-major nsrow x nscol block whose first nscol rows are
  // its own columns; the panels store the same numbers row by row, so both triangular solves
  // stream them in order and read each row's index once for the whole row.
  const int nsuper = static_cast<int>(factor_->nsuper);
  const int* super = static_cast<const int*>(factor_->super);
  const int* rowPointer = static_cast<const int*>(factor_->pi);
  const int* valuePointer = static_cast<const int*>(factor_->px);
  const int* rows = static_cast<const int*>(factor_->s);
  const double* x = static_cast<const double*>(factor_->x);
  superStart_.assign(super, super + nsuper + 1);
  belowStart_.resize(nsuper + 1);
  panelStart_.resize(nsuper + 1);
  std::size_t belowCount = 0, panelCount = 0;
  for (int s = 0; s < nsuper; ++s) {
    const int width = super[s + 1] - super[s], height = rowPointer[s + 1] - rowPointer[s];
    belowCount += static_cast<std::size_t>(height - width);
    panelCount += static_cast<std::size_t>(height) * static_cast<std::size_t>(width);
  }
  belowRows_.resize(belowCount);
  panels.resize(panelCount);
  belowCount = panelCount = 0;
  for (int s = 0; s < nsuper; ++s) {
    const int width = super[s + 1] - super[s], height = rowPointer[s + 1] - rowPointer[s];
    belowStart_[s] = static_cast<int>(belowCount);
    panelStart_[s] = panelCount;
    for (int i = width; i < height; ++i) belowRows_[belowCount++] = rows[rowPointer[s] + i];
    const double* block = x + valuePointer[s];
    for (int i = 0; i < height; ++i)
      for (int c = 0; c < width; ++c) panels[panelCount++] = static_cast<T>(block[i + c * height]);
  }
  belowStart_[nsuper] = static_cast<int>(belowCount);
  panelStart_[nsuper] = panelCount;
}

template <int W>
double* SparseCholesky::permuteIn(const double* data) {
  // work_ = P b with the W right-hand sides interleaved, so each entry of L updates W contiguous
  // values.
  const std::size_t stride = static_cast<std::size_t>(size_);
  double* z = work_.data();
  for (int k = 0; k < size_; ++k)
    for (int c = 0; c < W; ++c) z[W * k + c] = data[c * stride + perm_[k]];
  return z;
}

template <int W>
void SparseCholesky::permuteOut(double* data) const {
  const std::size_t stride = static_cast<std::size_t>(size_);
  const double* z = work_.data();
  for (int k = 0; k < size_; ++k)
    for (int c = 0; c < W; ++c) data[c * stride + perm_[k]] = z[W * k + c];
}

template <int W>
void SparseCholesky::solveSimplicial(double* data) {
  // x = P^T L^{-T} L^{-1} P b with the W right-hand sides interleaved, so each nonzero of L
  // updates W contiguous values.
  const int n = size_;
  double* z = permuteIn<W>(data);
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
  permuteOut<W>(data);
}

template <class T, int W>
void SparseCholesky::solveSupernodal(const T* panels, double* data) {
  // The same two triangular solves over the packed panels (see packSupernodal).
  const int nsuper = static_cast<int>(superStart_.size()) - 1;
  double* z = permuteIn<W>(data);
  for (int s = 0; s < nsuper; ++s) {  // L z' = z
    const int first = superStart_[s], width = superStart_[s + 1] - first;
    const T* panel = panels + panelStart_[s];
    double* zs = z + W * first;
    for (int i = 0; i < width; ++i) {
      const T* row = panel + i * width;
      double acc[W];
      for (int c = 0; c < W; ++c) acc[c] = zs[W * i + c];
      for (int j = 0; j < i; ++j)
        for (int c = 0; c < W; ++c) acc[c] -= static_cast<double>(row[j]) * zs[W * j + c];
      for (int c = 0; c < W; ++c) zs[W * i + c] = acc[c] / static_cast<double>(row[i]);
    }
    const T* below = panel + width * width;
    for (int r = belowStart_[s]; r < belowStart_[s + 1]; ++r, below += width) {
      double acc[W] = {};
      for (int j = 0; j < width; ++j)
        for (int c = 0; c < W; ++c) acc[c] += static_cast<double>(below[j]) * zs[W * j + c];
      double* zi = z + W * belowRows_[r];
      for (int c = 0; c < W; ++c) zi[c] -= acc[c];
    }
  }
  for (int s = nsuper - 1; s >= 0; --s) {  // L^T z'' = z'
    const int first = superStart_[s], width = superStart_[s + 1] - first;
    const T* panel = panels + panelStart_[s];
    double* zs = z + W * first;
    const T* below = panel + width * width;
    for (int r = belowStart_[s]; r < belowStart_[s + 1]; ++r, below += width) {
      const double* zi = z + W * belowRows_[r];
      for (int j = 0; j < width; ++j)
        for (int c = 0; c < W; ++c) zs[W * j + c] -= static_cast<double>(below[j]) * zi[c];
    }
    for (int i = width - 1; i >= 0; --i) {
      const T* row = panel + i * width;
      for (int c = 0; c < W; ++c) zs[W * i + c] /= static_cast<double>(row[i]);
      for (int j = 0; j < i; ++j)
        for (int c = 0; c < W; ++c) zs[W * j + c] -= static_cast<double>(row[j]) * zs[W * i + c];
    }
  }
  permuteOut<W>(data);
}

void SparseCholesky::solveInPlace(double* data, int columns) {
  if (packed_) {
    const std::size_t stride = static_cast<std::size_t>(size_);
    const bool single = !panelsSingle_.empty();
    if (columns == 3) {
      if (single) return solveSupernodal<float, 3>(panelsSingle_.data(), data);
      return solveSupernodal<double, 3>(panels_.data(), data);
    }
    for (int c = 0; c < columns; ++c) {
      if (single)
        solveSupernodal<float, 1>(panelsSingle_.data(), data + c * stride);
      else
        solveSupernodal<double, 1>(panels_.data(), data + c * stride);
    }
    return;
  }
  if (columns == 3) return solveSimplicial<3>(data);
  if (columns == 1) return solveSimplicial<1>(data);
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
