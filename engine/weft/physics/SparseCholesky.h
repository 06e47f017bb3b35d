#pragma once
// CHOLMOD Cholesky factorisation of a sparse symmetric positive definite matrix, factorised once
// and reused for every solve until the matrix changes (DiffCloth Sec. 3.1: "P is a constant
// matrix that can be prefactorized"). CHOLMOD orders and factorises; the solves are our own
// loops over the factor, with no allocation per solve. Two uses, two layouts:
//  - Use::Solve (P of the PD global step, whose solves are results): a simplicial L L^T in
//    double precision, the right-hand sides interleaved (for the small, many-times-solved
//    systems of cloth about twice as fast as cholmod_solve2).
//  - Use::Preconditioner (the clamped Hessian K+ = P - Delta P+ that preconditions GMRES in the
//    Newton contact solve and the adjoint): ordered by the better of AMD and nested dissection;
//    where CHOLMOD factorises it in supernodes (enough flops per entry of L), kept as their
//    dense row-major panels, in single precision once L outgrows the cache (the arithmetic
//    stays double); otherwise simplicial as above. A preconditioner only needs to be close:
//    a float factor changes the solve by about 1e-7 relative, and it halves the memory the
//    solve streams, which is what a large solve is bound by (docs/how-it-works/forward.md,
//    "Measured on the way").
#include <weft/core/Types.h>

#include <Eigen/SparseCore>

#include <vector>

struct cholmod_common_struct;
struct cholmod_factor_struct;
struct cholmod_dense_struct;

namespace weft {

class SparseCholesky {
 public:
  enum class Use { Solve, Preconditioner };
  explicit SparseCholesky(Use use = Use::Solve);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Factorises a symmetric positive definite matrix (only its lower triangle is read). The
  // symbolic analysis is kept while the sparsity pattern stays the same.
  // Returns false if the matrix is not positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& matrix);
  // The matrices to factorise are (k m) x (k m) with unknown d m + i belonging to node i of the
  // m x m `nodeGraph` (a NodeMatrix's flat index, k = 3 for K+): from the next analysis on, the
  // unknowns are ordered by a fill-reducing ordering of the node graph (the better of AMD and
  // nested dissection, as CHOLMOD picks), each node's k unknowns together. Ordering the node
  // graph is much cheaper than ordering the full matrix and finds as little fill (Slope K+ at
  // 48^2 quads: see SparseCholeskyTest).
  void orderByNodes(const Eigen::SparseMatrix<double>& nodeGraph);
  bool factorized() const { return factorized_; }
  // How the current factor is kept (for diagnostics and tests).
  enum class Layout { None, Simplicial, PanelsDouble, PanelsSingle };
  Layout layout() const {
    if (!factorized_) return Layout::None;
    if (!packed_) return Layout::Simplicial;
    return panelsSingle_.empty() ? Layout::PanelsDouble : Layout::PanelsSingle;
  }
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

  // b <- A^{-1} b, for an n x k column-major block (k right-hand sides solved together).
  void solveInPlace(double* data, int columns);
  void solveInPlace(NodeMatrix& b) { solveInPlace(b.data(), 3); }
  void solveInPlace(Eigen::VectorXd& b) { solveInPlace(b.data(), 1); }

 private:
  template <int W>
  double* permuteIn(const double* data);  // the permuted, interleaved copy in work_
  template <int W>
  void permuteOut(double* data) const;
  template <int W>
  void solveSimplicial(double* data);
  template <class T>
  void packSupernodal(std::vector<T>& panels);
  template <class T, int W>
  void solveSupernodal(const T* panels, double* data);

  Use use_;
  cholmod_common_struct* common_;
  cholmod_factor_struct* factor_ =
      nullptr;  // the numeric factor (Use::Solve only; freed once packed)
  cholmod_factor_struct* symbolic_ =
      nullptr;  // cholmod_analyze's result, kept while the pattern is
  cholmod_dense_struct *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;
  bool factorized_ = false;
  bool packed_ = false;  // L is in the panels (Use::Preconditioner), not in factor_
  // Simplicial L (views into factor_).
  const int* colStart_ = nullptr;
  const int* rowIndex_ = nullptr;
  const double* values_ = nullptr;
  // Supernodal L, packed: supernode s holds columns [superStart_[s], superStart_[s + 1]); its
  // w x w lower-triangular diagonal block and then its rows below it, each w values row-major,
  // from panelStart_[s]; the rows below are belowRows_[belowStart_[s] .. belowStart_[s + 1]).
  std::vector<int> superStart_, belowStart_, belowRows_;
  std::vector<std::size_t> panelStart_;
  std::vector<double> panels_;       // small factors: in cache, double is as fast
  std::vector<float> panelsSingle_;  // large factors: streamed from memory, float halves it
  std::vector<int> perm_;
  std::vector<int> nodeOrder_;  // orderByNodes: the node graph's ordering (empty: CHOLMOD orders)
  std::vector<double> work_;
  Eigen::SparseMatrix<double> lower_;  // kept: CHOLMOD views its arrays
  int size_ = 0;
  long long patternNonZeros_ = -1;
  double factorFlops_ = 0.0, factorEntries_ = 0.0;
};

}  // namespace weft
