#pragma once
// Anderson acceleration (type II, window m) of a fixed-point iteration x <- G(x), as applied
// to local-global solvers by Peng et al. 2018. The caller keeps the energy safeguard: when an
// accelerated iterate raises the energy it falls back to the plain iterate and restarts.

#include <Eigen/Core>

namespace weft {

class AndersonAccelerator {
 public:
  void reset(Eigen::Index dimension, int window);
  void restart() { count_ = 0, hasPrevious_ = false; }
  // Given the current iterate x and its image g = G(x), writes the next iterate to `out`.
  void next(const double* x, const double* g, double* out);

 private:
  Eigen::MatrixXd dF_, dG_, gram_;
  Eigen::VectorXd f_, fPrev_, gPrev_;
  int window_ = 0, count_ = 0, head_ = 0;
  bool hasPrevious_ = false;
};

}  // namespace weft
