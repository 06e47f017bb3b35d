#pragma once
// L-BFGS-B (Byrd, Lu, Nocedal, Zhu 1995) through LBFGSpp's LBFGSBSolver (Debian liblbfgspp-dev):
// quasi-Newton steps inside the box, so bounds are honoured at every evaluated point. This is the
// optimiser DiffCloth uses for its system-identification and inverse-design tasks (Sec. 6).

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
