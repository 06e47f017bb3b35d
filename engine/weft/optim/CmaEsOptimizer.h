#pragma once
// CMA-ES, the covariance matrix adaptation evolution strategy, as in N. Hansen, "The CMA Evolution
// Strategy: A Tutorial" (arXiv:1604.00772; Table 1 for the default parameters, Fig. 6 / Appendix
// A for the algorithm): (mu/mu_w, lambda) selection with lambda = 4 + floor(3 ln n) and
// mu = lambda/2 logarithmic weights, cumulative step-size adaptation, and the rank-one plus
// rank-mu covariance update, C decomposed by Eigen's SelfAdjointEigenSolver. The gradient-free
// baseline of DiffCloth (Sec. 5.2, Tables 2-3, Fig. 4): it only asks for values, so each
// evaluation of a simulation costs its forward steps alone.
//
// Box, scaling, repair and initial step size: SearchBox (projection repair, the repaired point
// evaluated and used in the update; sigma0 a quarter of each variable's box width). The first
// evaluation is the starting point itself, so the log starts at the initial loss as the
// gradient-based methods' logs do. Random numbers: std::mt19937_64 seeded with settings.seed, one
// std::normal_distribution per run, so the same seed gives the same log, bit for bit, on the
// same build.
//
// Stops (the tutorial's termination criteria, Appendix B.3, those that apply here): the budget or
// the evaluation cap (Optimizer); settings.maxIterations generations; TolX (sigma times every
// axis of C below 1e-12 of the initial step); TolFun relative (best losses of the last
// 10 + ceil(30 n / lambda) generations and all of the current one within settings.lossTolerance
// of each other, relative to the loss); ConditionCov (condition number of C above 1e14).

#include <weft/optim/Optimizer.h>

namespace weft {

class CmaEsOptimizer : public Optimizer {
 public:
  using Optimizer::Optimizer;
  std::string name() const override { return "cmaes"; }
  bool usesGradient() const override { return false; }

 protected:
  std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) override;
};

}  // namespace weft
