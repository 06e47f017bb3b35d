#pragma once
// L-BFGS-B (Byrd, Lu, Nocedal, Zhu 1995) on LBFGSpp's parts (Debian liblbfgspp-dev): its compact
// BFGS matrix, generalised Cauchy point, subspace minimisation and More-Thuente line search, so
// bounds are honoured at every evaluated point. This is the optimiser DiffCloth uses for its
// system-identification and inverse-design tasks (Sec. 6).
//
// The iteration is Weft's own (the loop of LBFGSpp's LBFGSBSolver, which it reproduces
// evaluation for evaluation with the default settings; AnalyticOptimizerTest), for two settings
// that solver does not have, both for gradients that jitter at small scales (the Sock's;
// docs/how-it-works/optimisers.md):
// - OptimizerSettings::lbfgsbFirstStep: the length of the first trial step, in optimiser
//   coordinates, along the normalised direction to the first Cauchy point. LBFGSpp tries 1, a
//   box-sized step on most tasks: the loss there is far off, the line search comes back to a
//   tiny step, and the first curvature pair is measured over that step, where the jitter is
//   all it sees.
// - OptimizerSettings::lbfgsbMinCurvatureStep: curvature pairs (s, y) with |s| below this length
//   are not added to the BFGS matrix (the step is still taken). Over such a step |y| is the
//   gradient's jitter, not its curvature, and one such pair makes every later step as short
//   (a skip in the spirit of the lengthened pairs of Shi, Xuan, Oztoprak, Nocedal 2022, without
//   their extra gradient evaluation).

#include <weft/optim/Optimizer.h>

namespace weft {

class LbfgsbOptimizer : public Optimizer {
 public:
  using Optimizer::Optimizer;
  std::string name() const override { return "lbfgsb"; }

 protected:
  std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) override;
};

}  // namespace weft
