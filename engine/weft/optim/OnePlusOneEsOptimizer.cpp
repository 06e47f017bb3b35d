#include <weft/optim/OnePlusOneEsOptimizer.h>

#include <weft/optim/SearchBox.h>

#include <cmath>
#include <random>

namespace weft {

std::string OnePlusOneEsOptimizer::run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                                       const Eigen::VectorXd& upper) {
  const int n = static_cast<int>(x.size());
  const SearchBox box(x, lower, upper);
  std::mt19937_64 random(settings().seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double grow = std::exp(1.0 / 3.0), shrink = std::exp(-1.0 / 12.0);  // Kern et al. 2004

  Eigen::VectorXd parent = Eigen::VectorXd::Zero(n);  // search coordinates: the start is 0
  double parentLoss = evaluateValue(box.repairedCoordinates(parent));
  if (n == 0) return "no parameters";
  const double sigma0 = SearchBox::kInitialStepFraction;
  double sigma = sigma0;
  Eigen::VectorXd z(n);
  for (;;) {
    if (settings().maxIterations > 0 && iterations_ >= settings().maxIterations)
      return "max iterations";
    if (sigma < 1e-12 * sigma0) return "converged: step size";
    for (int i = 0; i < n; ++i) z[i] = normal(random);
    const Eigen::VectorXd at = box.repairedCoordinates(parent + sigma * z);
    const double loss = evaluateValue(at);
    ++iterations_;
    // NaN compares false: a failed evaluation is a failure.
    if (loss < parentLoss || (std::isnan(parentLoss) && !std::isnan(loss))) {
      parent = box.toSearch(at), parentLoss = loss;
      sigma *= grow;
    } else {
      if (loss == parentLoss) parent = box.toSearch(at);
      sigma *= shrink;
    }
  }
}

}  // namespace weft
