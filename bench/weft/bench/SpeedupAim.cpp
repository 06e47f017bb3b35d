#include "SpeedupAim.h"

#include <cstdio>

namespace weft::bench {

SpeedupAim judgeSpeedupAim(long long lbfgsbSteps, long long cmaesSteps, long long budget,
                           double factor) {
  char fifth[32];
  std::snprintf(fifth, sizeof fifth, "%g", factor);
  SpeedupAim aim;
  if (lbfgsbSteps <= 0) {
    aim.verdict = SpeedupAim::Verdict::NotMet;
    aim.text = "not met: L-BFGS-B does not reach it";
  } else if (cmaesSteps > 0) {
    aim.ratio = double(cmaesSteps) / double(lbfgsbSteps);
    aim.verdict = aim.ratio >= factor ? SpeedupAim::Verdict::Met : SpeedupAim::Verdict::NotMet;
    aim.text = aim.ratio >= factor ? "met" : std::string("not met: under ") + fifth;
  } else {
    aim.ratio = double(budget) / double(lbfgsbSteps);
    aim.lowerBound = true;
    if (aim.ratio >= factor) {
      aim.verdict = SpeedupAim::Verdict::Met;
      aim.text = "met (CMA-ES does not reach it)";
    } else {
      aim.verdict = SpeedupAim::Verdict::NotShown;
      aim.text = std::string("not shown: CMA-ES does not reach it, and the budget is under ") +
                 fifth + " x L-BFGS-B's steps";
    }
  }
  return aim;
}

}  // namespace weft::bench
