#pragma once
// Restarted GMRES with right preconditioning on m x 3 blocks (one 3m vector): solves A z = b
// given out = A in and out = B in (B approximates A^-1). Right preconditioning keeps the
// minimised residual the true one, |b - A z|, so a tolerance means the same whatever B is.
// Used by the forward semismooth-Newton contact solve (A = its non-symmetric Jacobian) and by
// the adjoint (diff/GmresSolver, A = (P - Delta P - Delta R)^T).

#include <weft/core/Types.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace weft {

struct GmresResult {
  bool converged = false;
  int iterations = 0;     // products with A (= applications of B)
  double residual = 0.0;  // |b - A z| / |b| at the returned z
};

class Gmres {
 public:
  // z is overwritten. The iteration starts from zero, or with `warmStart` from the z passed in
  // (when it has b's shape and is finite). Stops when |b - A z| < tolerance |b| after at least
  // minIterations products, after maxIterations products, or on stagnation.
  template <class Apply, class Precondition>
  GmresResult solve(Apply&& apply, Precondition&& precondition, const NodeMatrix& b, NodeMatrix& z,
                    double tolerance, int maxIterations, int restart = 50, bool warmStart = false,
                    int minIterations = 0) {
    GmresResult result;
    const int m = static_cast<int>(b.rows());
    const double bNorm = b.norm();
    const bool fromGuess =
        warmStart && z.rows() == m && z.cols() == 3 && z.allFinite() && bNorm > 0.0;
    if (!fromGuess) z.setZero(m, 3);
    if (bNorm == 0.0) {
      residual_ = b;
      result.converged = true;
      return result;
    }
    restart = std::max(1, restart);
    if (static_cast<int>(basis_.size()) < restart + 1) {
      basis_.resize(restart + 1);
      preconditioned_.resize(restart);
    }
    // Operators may write through raw pointers: every output is sized before use.
    work_.resize(m, 3);
    for (NodeMatrix& p : preconditioned_) p.resize(m, 3);
    if (fromGuess) {
      apply(z, work_);
      residual_ = b - work_;
    } else {
      residual_ = b;  // b - A z_0 with z_0 = 0
    }
    double residualNorm = residual_.norm();
    result.residual = residualNorm / bNorm;
    if (fromGuess && result.residual < tolerance && minIterations <= 0) {
      result.converged = true;
      return result;
    }
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(restart + 1, restart);
    Eigen::VectorXd cs(restart), sn(restart), s(restart + 1);
    while (result.iterations < maxIterations) {
      basis_[0] = residual_ / residualNorm;
      s.setZero();
      s[0] = residualNorm;
      h.setZero();
      int j = 0;
      bool done = false;
      for (; j < restart && result.iterations < maxIterations; ++j) {
        precondition(basis_[j], preconditioned_[j]);
        apply(preconditioned_[j], work_);
        ++result.iterations;
        // Modified Gram-Schmidt against the basis.
        for (int i = 0; i <= j; ++i) {
          h(i, j) = (work_.array() * basis_[i].array()).sum();
          work_ -= h(i, j) * basis_[i];
        }
        h(j + 1, j) = work_.norm();
        const bool breakdown = !(h(j + 1, j) > 1e-14 * std::abs(h(j, j)) + 1e-300);
        if (!breakdown) basis_[j + 1] = work_ / h(j + 1, j);
        // Apply the previous Givens rotations to column j, then one that zeroes h(j+1, j).
        for (int i = 0; i < j; ++i) {
          const double a = h(i, j), c = h(i + 1, j);
          h(i, j) = cs[i] * a + sn[i] * c;
          h(i + 1, j) = -sn[i] * a + cs[i] * c;
        }
        const double a = h(j, j), c = h(j + 1, j);
        const double r = std::hypot(a, c);
        cs[j] = r > 0.0 ? a / r : 1.0;
        sn[j] = r > 0.0 ? c / r : 0.0;
        h(j, j) = r;
        h(j + 1, j) = 0.0;
        s[j + 1] = -sn[j] * s[j];
        s[j] = cs[j] * s[j];
        if ((std::abs(s[j + 1]) < tolerance * bNorm && result.iterations >= minIterations) ||
            breakdown) {
          ++j;
          done = true;
          break;
        }
      }
      // z += B V y with H y = s (upper triangular, j columns).
      if (j > 0) {
        const Eigen::VectorXd y =
            h.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(s.head(j));
        for (int i = 0; i < j; ++i) z += y[i] * preconditioned_[i];
      }
      // The true residual decides (the recurrence's estimate drifts in round-off).
      apply(z, work_);
      residual_ = b - work_;
      const double previous = residualNorm;
      residualNorm = residual_.norm();
      result.residual = residualNorm / bNorm;
      if (!std::isfinite(result.residual)) return result;
      if (result.residual < tolerance && result.iterations >= minIterations) {
        result.converged = true;
        return result;
      }
      if (done && !(residualNorm < 0.5 * previous)) return result;  // stagnated at breakdown
    }
    return result;
  }

  // b - A z at the z the last solve returned (so A z = b - residual() costs no product).
  const NodeMatrix& residual() const { return residual_; }

 private:
  std::vector<NodeMatrix> basis_, preconditioned_;  // V_j and B V_j
  NodeMatrix residual_, work_;
};

}  // namespace weft
