#pragma once
// The (1+1)-ES with the one-fifth success rule (Rechenberg 1973), in the form of Kern, Müller,
// Hansen, Büche, Ocenasek and Koumoutsakos 2004, "Learning probability distributions in
// continuous evolutionary algorithms - a comparative review" (Natural Computing 3): one parent,
// one isotropic Gaussian offspring per iteration, which replaces the parent unless worse; the
// step size grows by exp(1/3) on a success and shrinks by exp(1/3)^(-1/4) = exp(-1/12) otherwise,
// so it is stationary at a success rate of 1/5 (exp(1/3)^(1/5) exp(-1/12)^(4/5) = 1). The second
// gradient-free baseline of DiffCloth's Tables 2-3.
//
// One difference from Kern et al., for the box: a success is a strict improvement. An offspring
// that ties with its parent (both repaired onto the same point of the boundary, or a flat loss)
// still replaces it, but counts as a failure, so the step size shrinks at a minimum on the
// boundary instead of growing without end.
//
// Box, scaling, projection repair and initial step size (a quarter of each variable's box width):
// SearchBox. The first evaluation is the start. Seeded: std::mt19937_64 from settings.seed, same
// seed, same log. Stops on the budget, the evaluation cap, settings.maxIterations offspring, or a
// step size below 1e-12 of the initial one.

#include <weft/optim/Optimizer.h>

namespace weft {

class OnePlusOneEsOptimizer : public Optimizer {
 public:
  using Optimizer::Optimizer;
  std::string name() const override { return "es1p1"; }
  bool usesGradient() const override { return false; }

 protected:
  std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) override;
};

}  // namespace weft
