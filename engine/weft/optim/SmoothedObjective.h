#pragma once
// Gaussian smoothing of an objective, for landscapes whose true gradient is useless (chaotic
// runs, contact switching: DiffCloth's limitation 3). L_s(x) = E_u[L(x + s u)], u ~ N(0, I) in
// optimiser coordinates, whose gradient is E_u[grad L(x + s u)] (randomised smoothing, Nesterov
// and Spokoiny 2017), estimated from `pairs` antithetic pairs x +- s u_k:
//
//   g = (1 / K) sum_k g_k,   g_k = (grad L(x + s u_k) + grad L(x - s u_k)) / 2.
//
// The u_k are drawn once from the seed and used at every x (common random numbers), so the
// function the optimiser sees is a fixed average of 2K shifted copies of L: deterministic, and
// smooth where they overlap, so line searches work on it. Bias, stated: exact for a quadratic
// (a pair cancels every odd term); a bump a cos(w x) keeps its shape with its gradient scaled by
// exp(-s^2 w^2 / 2): features narrower than s are flattened, wider ones kept. Variance: the
// estimate's sampling variance sum_k |g_k - g|^2 / (K (K - 1)) is reported with every gradient.
// A sample outside the optimiser's box is projected onto it (the inner objective is never asked
// for a point the box excludes), which makes the pairs lopsided within s of a bound.

#include <weft/optim/Objective.h>

#include <Eigen/Core>

namespace weft {

class SmoothedObjective final : public Objective {
 public:
  // sigma > 0 (optimiser coordinates), pairs >= 1; samples are projected into [lower, upper]
  // (empty: unbounded).
  SmoothedObjective(Objective& inner, double sigma, int pairs, unsigned long long seed,
                    const Eigen::VectorXd& lower = {}, const Eigen::VectorXd& upper = {});

  int dimension() const override { return inner_.dimension(); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) override;
  double value(const Eigen::VectorXd& x) override;
  long long stepsPerEvaluation() const override {
    return 2LL * pairs_ * inner_.stepsPerEvaluation();
  }
  long long stepsPerValue() const override { return 2LL * pairs_ * inner_.stepsPerValue(); }
  // The sampling standard error of the last gradient relative to its norm, plus the largest
  // relative error of the 2K gradients it averages (Objective::lastGradientError of the inner
  // objective): what the estimate may be off from the smoothed gradient.
  double lastGradientError() const override { return lastError_; }
  // The last gradient's sampling variance (trace of the estimate's covariance).
  double lastGradientVariance() const { return lastVariance_; }
  double sigma() const { return sigma_; }
  int pairs() const { return pairs_; }

 private:
  Objective& inner_;
  double sigma_;
  int pairs_;
  Eigen::MatrixXd directions_;  // dimension x pairs, the u_k
  Eigen::VectorXd lower_, upper_;
  void shift(const Eigen::VectorXd& x, int k, double sign);  // shifted_ = x + sign s u_k, boxed
  Eigen::VectorXd shifted_, sampleGradient_, pairGradient_;
  Eigen::MatrixXd pairGradients_;
  double lastError_ = 0.0, lastVariance_ = 0.0;
};

}  // namespace weft
