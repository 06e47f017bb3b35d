#include "LossEnvelope.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::bench {

LossCurve minimumEnvelope(const std::vector<LossCurve>& runs) {
  const double inf = std::numeric_limits<double>::infinity();
  // Every (steps, loss) of every run, by steps; then one running minimum over them all, which is
  // the minimum over runs of each run's running minimum.
  std::vector<std::pair<long long, double>> points;
  for (const LossCurve& run : runs)
    for (std::size_t i = 0; i < run.steps.size(); ++i)
      points.emplace_back(run.steps[i], std::isnan(run.loss[i]) ? inf : run.loss[i]);
  std::stable_sort(points.begin(), points.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  LossCurve envelope;
  double best = inf;
  for (const auto& [steps, loss] : points) {
    best = std::min(best, loss);
    if (!envelope.steps.empty() && envelope.steps.back() == steps) {
      envelope.loss.back() = best;
    } else {
      envelope.steps.push_back(steps);
      envelope.loss.push_back(best);
    }
  }
  return envelope;
}

double lossAt(const LossCurve& envelope, long long steps) {
  const auto it = std::upper_bound(envelope.steps.begin(), envelope.steps.end(), steps);
  if (it == envelope.steps.begin()) return std::numeric_limits<double>::infinity();
  return envelope.loss[static_cast<std::size_t>(it - envelope.steps.begin()) - 1];
}

long long stepsToReach(const LossCurve& envelope, double loss) {
  for (std::size_t i = 0; i < envelope.steps.size(); ++i)
    if (envelope.loss[i] <= loss) return envelope.steps[i];
  return -1;
}

}  // namespace weft::bench
