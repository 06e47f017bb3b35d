#pragma once
// `weft bench distribution` (DistributionBench.cpp): what handing out work items over the run's
// processes costs (serially, or under mpirun), and the wall time the paper's comparison would
// take on P ranks, projected from the measured runs of a finished comparison.

#include <weft/distributed/WorkDistributor.h>

#include <string>
#include <vector>

namespace weft::bench {

struct DistributionBenchOptions {
  bool quick = false;
  // A finished `weft bench applications` comparison's runs/ folder (its runs' wall seconds are
  // the work items projected); empty: docs/runs/full.
  std::string store;
  // Wall seconds of the comparison's part that no rank shares (set-up, the timed passes, the
  // tables): applications.md's "in this invocation" figure for a resume with every run stored.
  double serialSeconds = 111.6;
  std::vector<int> ranks{1, 2, 8, 32, 128};  // projected
  WorkDistributor* workers = nullptr;        // this launch's processes
};

// The makespan of `durations` handed out in order, each to the first of `ranks` processes to
// become free (what WorkDistributor::map does), plus `perItem` seconds of hand-out per item.
double listScheduleSeconds(const std::vector<double>& durations, int ranks, double perItem);

// Rank 0 writes distribution.csv and distribution.md into `outDir` (staged); returns 0.
int runDistributionBench(const DistributionBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
