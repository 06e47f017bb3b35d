#pragma once
// DiffCloth's published figures for its Sec. 6 tasks (Li et al. 2022, Tables 2, 3 and 4), so that
// `weft bench applications` can print its own measurements beside them. Keyed by the name
// `--tasks` takes; the paper has no row for the Flying Napkin (Fig. 4 only) or wind_sysid.

#include <string>

namespace weft::bench::paper {

struct PublishedTaskFigures {
  const char* task;       // weft's task name
  const char* title;      // the paper's row name
  int parameters;         // Table 2 "Param #"
  int seeds;              // Table 2 "Seed #"
  double minInitialLoss;  // Table 2, in the paper's own loss units
  // Table 2, % of the minimum initial loss: L-BFGS-B, CMA-ES, (1+1)-ES final; CMA-ES and (1+1)-ES
  // at L-BFGS-B's convergence step count ("Equal Step #").
  double finalPercent[3];
  double equalStepPercent[2];
  long long convergenceSteps[3];     // Table 3, L-BFGS-B (forward + backward), CMA-ES, (1+1)-ES
  double iterativeConvergedPercent;  // Table 3 "Iter. Conv. %"
  int dof;                           // Table 4
  int steps;                         // Table 4 "Time Steps"
  const char* timeStep;              // Table 4 "h [s]"
  double forwardSeconds, backwardSeconds;  // Table 4, mean per pass on an 80-core workstation
};

// nullptr for a task the paper does not tabulate.
const PublishedTaskFigures* publishedFigures(const std::string& task);

}  // namespace weft::bench::paper
