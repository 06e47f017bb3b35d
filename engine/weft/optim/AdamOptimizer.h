#pragma once
// Adam (Kingma and Ba 2015) with projection onto the box after every step: the first-order method
// the differentiable-simulation literature commonly compares L-BFGS against. One evaluation per
// iteration. Deterministic: the seed is recorded but nothing here is random.

#include <weft/optim/Optimizer.h>

namespace weft {

class AdamOptimizer : public Optimizer {
 public:
  using Optimizer::Optimizer;
  std::string name() const override { return "adam"; }

 protected:
  std::string run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) override;
};

}  // namespace weft
