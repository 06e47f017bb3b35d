#include <weft/diff/SolutionHistory.h>

#include <weft/diff/AdjointLinearSolver.h>

namespace weft {

void SolutionHistory::add(const NodeMatrix& z, const NodeMatrix& product) {
  if (capacity_ == 0 || z.size() == 0 || product.rows() != z.rows()) return;
  if (!z.allFinite() || !product.allFinite() || product.isZero(0.0)) return;
  if (static_cast<int>(solutions_.size()) < capacity_) {
    solutions_.resize(capacity_);
    products_.resize(capacity_);
    gram_ = Eigen::MatrixXd::Zero(capacity_, capacity_);
  }
  // Newest first: every kept pair moves down one place (swaps, no copies).
  const int kept = std::min(size_, capacity_ - 1);
  for (int i = kept; i > 0; --i) {
    solutions_[i].swap(solutions_[i - 1]);
    products_[i].swap(products_[i - 1]);
  }
  if (kept > 0) {
    const Eigen::MatrixXd shifted = gram_.topLeftCorner(kept, kept);
    gram_.block(1, 1, kept, kept) = shifted;
  }
  size_ = kept + 1;
  solutions_[0] = z;
  products_[0] = product;
  for (int i = 0; i < size_; ++i) gram_(0, i) = gram_(i, 0) = blockDot(products_[0], products_[i]);
}

bool SolutionHistory::guess(const NodeMatrix& rhs, NodeMatrix& z) const {
  if (size_ == 0 || rhs.rows() != solutions_[0].rows()) return false;
  // c from the normal equations G c = W^T rhs, G = W^T W, through G's eigen-decomposition with
  // directions below kRelativeCutoff of its largest eigenvalue dropped (the products of
  // consecutive solutions are nearly parallel).
  constexpr double kRelativeCutoff = 1e-12;
  Eigen::VectorXd projected(size_);
  for (int i = 0; i < size_; ++i) projected[i] = blockDot(products_[i], rhs);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram_.topLeftCorner(size_, size_));
  if (eigen.info() != Eigen::Success) return false;
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  const double cutoff = kRelativeCutoff * lambda.cwiseAbs().maxCoeff();
  Eigen::VectorXd along = eigen.eigenvectors().transpose() * projected;
  for (int i = 0; i < size_; ++i) along[i] = lambda[i] > cutoff ? along[i] / lambda[i] : 0.0;
  const Eigen::VectorXd c = eigen.eigenvectors() * along;
  if (!c.allFinite() || c.isZero(0.0)) return false;
  z = c[0] * solutions_[0];
  for (int i = 1; i < size_; ++i) z += c[i] * solutions_[i];
  return true;
}

}  // namespace weft
