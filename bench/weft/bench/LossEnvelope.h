#pragma once
// Loss against simulated steps, and the minimum envelope over seeds that DiffCloth plots and
// tabulates for its optimisers (Sec. 5.2 and Appendix C: "the loss is the minimum loss from each
// method's parallel runs as a function of the time steps they have consumed"; Tables 2-3 and
// Figs. 4, 9-11 use it): for each run the best loss seen so far, then the minimum over runs.

#include <vector>

namespace weft::bench {

// One run's evaluations in order: cumulative simulated steps and the loss of that evaluation;
// or an envelope: a non-increasing loss at increasing step counts.
struct LossCurve {
  std::vector<long long> steps;
  std::vector<double> loss;
};

// The minimum over `runs` of their running minima, given at every step count where some run
// evaluated (a failed evaluation, NaN, counts as no improvement).
LossCurve minimumEnvelope(const std::vector<LossCurve>& runs);

// The envelope's loss once `steps` steps are spent: +inf before its first point.
double lossAt(const LossCurve& envelope, long long steps);

// The first step count at which the envelope is at or below `loss`; -1 if it never is.
long long stepsToReach(const LossCurve& envelope, double loss);

}  // namespace weft::bench
