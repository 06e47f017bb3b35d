#include <weft/optim/CmaEsOptimizer.h>

#include <weft/optim/SearchBox.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace weft {
namespace {

// Sorts NaN last (a failed evaluation is the worst), keeping std::stable_sort's ordering strict.
double rankKey(double loss) {
  return std::isnan(loss) ? std::numeric_limits<double>::infinity() : loss;
}

}  // namespace

std::string CmaEsOptimizer::run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper) {
  const int n = static_cast<int>(x.size());
  const SearchBox box(x, lower, upper);
  std::mt19937_64 random(settings().seed);
  std::normal_distribution<double> normal(0.0, 1.0);

  // The start itself first: the log then begins at the initial loss.
  evaluateValue(box.repairedCoordinates(Eigen::VectorXd::Zero(n)));
  if (n == 0) return "no parameters";

  // Default strategy parameters (tutorial, Table 1). c_mu carries the 1/4 offset of the
  // tutorial's current revision: alpha_mu (1/4 + mu_eff + 1/mu_eff - 2) / ((n+2)^2 + alpha_mu
  // mu_eff / 2) with alpha_mu = 2.
  const double dn = n;
  const int lambda = 4 + static_cast<int>(std::floor(3.0 * std::log(dn)));
  const int mu = lambda / 2;
  Eigen::VectorXd weights(mu);
  for (int i = 0; i < mu; ++i) weights[i] = std::log((lambda + 1) / 2.0) - std::log(i + 1.0);
  weights /= weights.sum();
  const double muEff = 1.0 / weights.squaredNorm();
  const double cSigma = (muEff + 2.0) / (dn + muEff + 5.0);
  const double dSigma =
      1.0 + 2.0 * std::max(0.0, std::sqrt((muEff - 1.0) / (dn + 1.0)) - 1.0) + cSigma;
  const double cC = (4.0 + muEff / dn) / (dn + 4.0 + 2.0 * muEff / dn);
  const double c1 = 2.0 / ((dn + 1.3) * (dn + 1.3) + muEff);
  const double cMu = std::min(
      1.0 - c1, 2.0 * (0.25 + muEff + 1.0 / muEff - 2.0) / ((dn + 2.0) * (dn + 2.0) + muEff));
  const double chiN =
      std::sqrt(dn) * (1.0 - 1.0 / (4.0 * dn) + 1.0 / (21.0 * dn * dn));  // E|N(0, I)|
  // The decomposition C = B D^2 B^T is refreshed every lambda / ((c1 + c_mu) n 10) generations
  // (tutorial, Appendix B.2: C changes little per generation; O(n^2) per sample instead of
  // O(n^3) per generation).
  const int eigenInterval =
      std::max(1, static_cast<int>(std::ceil(lambda / ((c1 + cMu) * dn * 10.0))));
  const int historyLength = 10 + static_cast<int>(std::ceil(30.0 * dn / lambda));

  const double sigma0 = SearchBox::kInitialStepFraction;
  double sigma = sigma0;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);  // search coordinates: the start is 0
  Eigen::VectorXd pSigma = Eigen::VectorXd::Zero(n), pC = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(n, n), B = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd D = Eigen::VectorXd::Ones(n);  // square roots of C's eigenvalues
  int lastDecomposition = 0;

  Eigen::MatrixXd steps(n, lambda);  // y_k = (x_k - m) / sigma of the repaired samples
  std::vector<double> losses(lambda);
  std::vector<int> order(lambda);
  std::deque<double> bestHistory;
  Eigen::VectorXd z(n);
  for (int generation = 1;; ++generation) {
    if (settings().maxIterations > 0 && iterations_ >= settings().maxIterations)
      return "max iterations";
    // The generation's samples, evaluated together (spread over processes when the objective
    // is; the same draws, losses and log as one at a time).
    std::vector<Eigen::VectorXd> population(lambda);
    for (int k = 0; k < lambda; ++k) {
      for (int i = 0; i < n; ++i) z[i] = normal(random);
      population[k] = box.repairedCoordinates(mean + sigma * (B * D.cwiseProduct(z)));
      steps.col(k) = (box.toSearch(population[k]) - mean) / sigma;
    }
    losses = evaluateValues(population);
    ++iterations_;

    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return rankKey(losses[a]) < rankKey(losses[b]); });
    Eigen::MatrixXd selected(n, mu);
    for (int i = 0; i < mu; ++i) selected.col(i) = steps.col(order[i]);
    const Eigen::VectorXd yW = selected * weights;

    // Mean, then cumulative step-size adaptation: p_sigma accumulates C^{-1/2} y_w.
    mean += sigma * yW;
    const Eigen::VectorXd whitened = B * (B.transpose() * yW).cwiseQuotient(D);
    pSigma = (1.0 - cSigma) * pSigma + std::sqrt(cSigma * (2.0 - cSigma) * muEff) * whitened;
    const double pSigmaNorm = pSigma.norm();
    // h_sigma stalls the rank-one path while |p_sigma| is large (sigma about to grow).
    const bool hSigma = pSigmaNorm / std::sqrt(1.0 - std::pow(1.0 - cSigma, 2.0 * generation)) <
                        (1.4 + 2.0 / (dn + 1.0)) * chiN;
    pC = (1.0 - cC) * pC;
    if (hSigma) pC += std::sqrt(cC * (2.0 - cC) * muEff) * yW;
    const double lostVariance = hSigma ? 0.0 : c1 * cC * (2.0 - cC);

    // Rank-one (p_c p_c^T) plus rank-mu (sum w_i y_i y_i^T) update; the weights sum to 1.
    C = (1.0 - c1 - cMu + lostVariance) * C + c1 * pC * pC.transpose() +
        cMu * selected * weights.asDiagonal() * selected.transpose();
    sigma *= std::exp((cSigma / dSigma) * (pSigmaNorm / chiN - 1.0));

    if (generation - lastDecomposition >= eigenInterval) {
      lastDecomposition = generation;
      C = C.triangularView<Eigen::Upper>();
      C = C.selfadjointView<Eigen::Upper>();
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(C);
      if (eigen.info() != Eigen::Success || !eigen.eigenvalues().allFinite())
        return "stopped: covariance not decomposable";
      B = eigen.eigenvectors();
      D = eigen.eigenvalues().cwiseMax(std::numeric_limits<double>::min()).cwiseSqrt();
      if (D.maxCoeff() > 1e7 * D.minCoeff()) return "converged: covariance condition";
    }
    if (!std::isfinite(sigma)) return "stopped: step size not finite";

    // TolX: every coordinate's standard deviation and the evolution path are negligible.
    if (sigma * C.diagonal().cwiseSqrt().maxCoeff() < 1e-12 * sigma0 &&
        sigma * pC.cwiseAbs().maxCoeff() < 1e-12 * sigma0)
      return "converged: step size";
    // TolFun, relative: recent best losses and this generation's losses all agree.
    bestHistory.push_back(rankKey(losses[order[0]]));
    if (static_cast<int>(bestHistory.size()) > historyLength) bestHistory.pop_front();
    if (static_cast<int>(bestHistory.size()) == historyLength) {
      double lo = *std::min_element(bestHistory.begin(), bestHistory.end());
      double hi = *std::max_element(bestHistory.begin(), bestHistory.end());
      lo = std::min(lo, rankKey(losses[order.front()]));
      hi = std::max(hi, rankKey(losses[order.back()]));
      if (std::isfinite(hi) &&
          hi - lo <= settings().lossTolerance * std::max(std::abs(lo), std::abs(hi)))
        return "converged: loss change";
    }
  }
}

}  // namespace weft
