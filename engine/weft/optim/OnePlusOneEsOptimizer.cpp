#include <weft/optim/OnePlusOneEsOptimizer.h>

#include <weft/optim/SearchBox.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

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
  // One offspring per generation, so a generation cannot be spread over processes. What can: a
  // rejected offspring leaves the parent as it was and only shrinks sigma, so the next
  // `concurrency() - 1` offspring are known in advance if each one before them is rejected. They
  // are evaluated at once, speculatively; the entries stop at the first offspring that is not
  // rejected (evaluateValues), and the random stream goes back to just after its draw. The run
  // is the same as one offspring at a time, evaluation for evaluation.
  struct Draw {
    Eigen::VectorXd at;
    std::mt19937_64 random;  // the stream after this offspring's draw
    std::normal_distribution<double> normal;
    double sigma;  // the step size it was drawn with
  };
  Eigen::VectorXd z(n);
  for (;;) {
    std::vector<Draw> chain;
    std::string stop;
    double s = sigma;
    for (int j = 0; j < std::max(1, concurrency()); ++j, s *= shrink) {
      if (settings().maxIterations > 0 && iterations_ + j >= settings().maxIterations) {
        stop = "max iterations";
        break;
      }
      if (s < 1e-12 * sigma0) {
        stop = "converged: step size";
        break;
      }
      for (int i = 0; i < n; ++i) z[i] = normal(random);
      chain.push_back({box.repairedCoordinates(parent + s * z), random, normal, s});
    }
    if (chain.empty()) return stop;
    std::vector<Eigen::VectorXd> points;
    for (const Draw& d : chain) points.push_back(d.at);
    // Rejected: not better (NaN compares false: a failed evaluation is a failure), and not equal
    // either (an equal offspring replaces the parent).
    const auto rejected = [&](double loss) {
      ++iterations_;  // per logged offspring, as one at a time counts them
      return !(loss < parentLoss || (std::isnan(parentLoss) && !std::isnan(loss))) &&
             !(loss == parentLoss);
    };
    const std::vector<double> losses = evaluateValues(points, rejected);
    const std::size_t last = losses.size() - 1;
    random = chain[last].random, normal = chain[last].normal;
    const double loss = losses[last];
    const Eigen::VectorXd& at = chain[last].at;
    sigma = chain[last].sigma;
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
