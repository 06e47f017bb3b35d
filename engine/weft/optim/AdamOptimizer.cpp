#include <weft/optim/AdamOptimizer.h>

#include <algorithm>
#include <cmath>

namespace weft {

std::string AdamOptimizer::run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper) {
  const double beta1 = 0.9, beta2 = 0.999, epsilon = 1e-8;  // the paper's defaults
  const double lr = settings().learningRate;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(x.size()), v = Eigen::VectorXd::Zero(x.size()), g;
  double previous = evaluate(x, g);
  for (int t = 1;; ++t) {
    if (projectedGradientNorm(x, g, lower, upper) <= settings().gradientTolerance)
      return "converged: projected gradient";
    if (settings().maxIterations > 0 && iterations_ >= settings().maxIterations)
      return "max iterations";
    m = beta1 * m + (1.0 - beta1) * g;
    v = beta2 * v + (1.0 - beta2) * g.cwiseAbs2();
    const double c1 = 1.0 - std::pow(beta1, t), c2 = 1.0 - std::pow(beta2, t);
    const Eigen::VectorXd step = lr * (m / c1).array() / ((v / c2).array().sqrt() + epsilon);
    const Eigen::VectorXd next = (x - step).cwiseMax(lower).cwiseMin(upper);
    ++iterations_;
    if ((next - x).cwiseAbs().maxCoeff() == 0.0) return "converged: at a bound";
    x = next;
    const double loss = evaluate(x, g);
    // Adam does not decrease monotonically, so a tiny change is only a stop once it is tiny
    // relative to the loss (the plateau at the optimum), not a single small step.
    if (std::abs(previous - loss) <= settings().lossTolerance * std::max(std::abs(loss), 1e-300) &&
        t > 10)
      return "converged: loss change";
    previous = loss;
  }
}

}  // namespace weft
