#pragma once
// `weft bench applications` (ApplicationsBench.cpp, whose opening comment describes the files
// written): DiffCloth's comparison of L-BFGS-B with CMA-ES and the (1+1)-ES over the task table
// (ApplicationTasks.h), runs stored as they finish so that a comparison can be resumed.

#include "ApplicationTasks.h"

#include <weft/distributed/WorkDistributor.h>
#include <weft/optim/Optimizer.h>

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace weft::bench {

struct ApplicationsBenchOptions {
  std::vector<const ApplicationTask*> tasks;  // entries of kApplicationTasks, no repeats
  std::vector<int> seeds;                     // per task: its runs use seeds 1..seeds[t]
  // Which methods make runs (kApplicationMethods' order); stored runs of the others are still
  // read back and tabulated.
  std::array<bool, kApplicationMethodCount> methods{true, true, true};
  bool quick = false;    // each task's quick budget
  bool resume = false;   // continue from the runs stored in DIR.partial/ or DIR/runs/
  int threads = 1;       // OpenMP threads per run
  int jobs = 1;          // runs at once
  long long budget = 0;  // simulated steps per run, for every task; 0: each task's own
  // L-BFGS-B's first step and curvature-pair threshold (the other settings are the run's own).
  OptimizerSettings lbfgsb;
  // The DiffCloth release's garment meshes (an absolute folder holding them all); empty: the
  // tasks' own meshes.
  std::string paperMeshes;
  // The record of the build running (BuildRecord.h), stored with the runs and compared on resume.
  nlohmann::json build;
  // The processes the runs are spread over (MPI's ranks under mpirun; each run is made and
  // stored by one rank, rank 0 tabulates); nullptr: this process alone, --jobs at a time.
  WorkDistributor* workers = nullptr;
};

// Writes the comparison into `outDir` (staged; the runs are kept in `outDir`.partial/ until it is
// finished). Throws InputError for a budget too small for a task (naming --budget, as the command
// line does) and for a run store made with other settings or by another build.
int runApplicationsBench(const ApplicationsBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
