#include <weft/physics/AndersonAccelerator.h>

#include <Eigen/Dense>

namespace weft {

void AndersonAccelerator::reset(Eigen::Index dimension, int window) {
  window_ = window;
  dF_.setZero(dimension, window);
  dG_.setZero(dimension, window);
  gram_.setZero(window, window);
  f_.setZero(dimension);
  fPrev_.setZero(dimension);
  gPrev_.setZero(dimension);
  restart();
}

void AndersonAccelerator::next(const double* xp, const double* gp, double* outp) {
  const Eigen::Index n = f_.size();
  Eigen::Map<const Eigen::VectorXd> x(xp, n), g(gp, n);
  Eigen::Map<Eigen::VectorXd> out(outp, n);
  f_ = g - x;
  if (!hasPrevious_) {
    fPrev_ = f_;
    gPrev_ = g;
    hasPrevious_ = true;
    out = g;
    return;
  }
  const int col = head_;
  dF_.col(col) = f_ - fPrev_;
  dG_.col(col) = g - gPrev_;
  head_ = (head_ + 1) % window_;
  count_ = std::min(count_ + 1, window_);
  for (int j = 0; j < count_; ++j) gram_(col, j) = gram_(j, col) = dF_.col(col).dot(dF_.col(j));
  Eigen::VectorXd rhs(count_);
  for (int j = 0; j < count_; ++j) rhs[j] = dF_.col(j).dot(f_);
  // Least squares min |f - dF gamma| through the normal equations, lightly regularised.
  Eigen::MatrixXd a = gram_.topLeftCorner(count_, count_);
  a.diagonal().array() += 1e-12 * (a.trace() / count_ + 1e-300);
  const Eigen::VectorXd gamma = a.ldlt().solve(rhs);
  fPrev_ = f_;
  gPrev_ = g;
  out = g - dG_.leftCols(count_) * gamma;
  if (!out.allFinite()) {  // a singular history: take the plain step and start over
    out = g;
    restart();
  }
}

}  // namespace weft
