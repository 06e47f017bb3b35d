#include <weft/optim/SmoothedObjective.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace weft {

namespace {

// Standard normal samples by Box-Muller from std::mt19937_64 (whose stream the standard fixes,
// unlike std::normal_distribution's), so a seed gives the same directions everywhere.
class NormalStream {
 public:
  explicit NormalStream(unsigned long long seed) : engine_(seed) {}
  double next() {
    if (spare_) {
      spare_ = false;
      return second_;
    }
    constexpr double kTwoPi = 6.283185307179586;
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;          // [0, 1)
    const double r = std::sqrt(-2.0 * std::log(u1));
    second_ = r * std::sin(kTwoPi * u2);
    spare_ = true;
    return r * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
  bool spare_ = false;
  double second_ = 0.0;
};

}  // namespace

SmoothedObjective::SmoothedObjective(Objective& inner, double sigma, int pairs,
                                     unsigned long long seed, const Eigen::VectorXd& lower,
                                     const Eigen::VectorXd& upper)
    : inner_(inner), sigma_(sigma), pairs_(pairs), lower_(lower), upper_(upper) {
  if (!(sigma > 0.0) || pairs < 1)
    throw std::invalid_argument("SmoothedObjective: sigma must be > 0 and pairs >= 1");
  const int n = inner.dimension();
  directions_.resize(n, pairs);
  NormalStream normal(seed);
  for (int k = 0; k < pairs; ++k)
    for (int i = 0; i < n; ++i) directions_(i, k) = normal.next();
  pairGradients_.resize(n, pairs);
}

void SmoothedObjective::shift(const Eigen::VectorXd& x, int k, double sign) {
  shifted_ = x + sign * sigma_ * directions_.col(k);
  if (lower_.size() == shifted_.size()) shifted_ = shifted_.cwiseMax(lower_);
  if (upper_.size() == shifted_.size()) shifted_ = shifted_.cwiseMin(upper_);
}

double SmoothedObjective::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  double loss = 0.0, innerError = 0.0;
  for (int k = 0; k < pairs_; ++k) {
    pairGradient_.setZero(x.size());
    for (const double sign : {1.0, -1.0}) {
      shift(x, k, sign);
      loss += inner_.evaluate(shifted_, sampleGradient_);
      innerError = std::max(innerError, inner_.lastGradientError());
      pairGradient_ += 0.5 * sampleGradient_;
    }
    pairGradients_.col(k) = pairGradient_;
  }
  gradient = pairGradients_.rowwise().mean();
  lastVariance_ = pairs_ > 1 ? (pairGradients_.colwise() - gradient).squaredNorm() /
                                   (static_cast<double>(pairs_) * (pairs_ - 1))
                             : 0.0;
  const double norm = gradient.norm();
  lastError_ = (norm > 0.0 ? std::sqrt(lastVariance_) / norm : 0.0) + innerError;
  return loss / (2.0 * pairs_);
}

double SmoothedObjective::value(const Eigen::VectorXd& x) {
  double loss = 0.0;
  for (int k = 0; k < pairs_; ++k)
    for (const double sign : {1.0, -1.0}) {
      shift(x, k, sign);
      loss += inner_.value(shifted_);
    }
  return loss / (2.0 * pairs_);
}

}  // namespace weft
