#pragma once
// `weft sweep`: one simulation per combination of listed values of scene paths (any `--set`
// path), each run's summary (summary.json's figures) gathered into one CSV row. The runs are
// work items (weft/distributed/WorkDistributor.h): serial, or spread over MPI ranks, with the
// same file either way apart from the timing columns at its end.

#include <weft/distributed/WorkDistributor.h>
#include <weft/scene/SceneLoader.h>

#include <string>
#include <vector>

namespace weft {

// One `--set-grid PATH=a,b,c`: a path and its values as typed (commas inside [] {} or quotes
// do not split, so "PATH=[0,1,0],[1,0,0]" is two vectors).
struct SweepAxis {
  std::string path;
  std::vector<std::string> values;
};

// Throws InputError `<file>: --set-grid <text>: <what>` for text without '=', an empty path or
// an empty value.
SweepAxis parseSweepAxis(const std::string& text, const std::string& file);

struct SweepSettings {
  std::string sceneFile;
  std::vector<SceneOverride> overrides;  // --set, applied before each combination's values
  std::vector<SweepAxis> axes;           // the first varies slowest
  int steps = -1;                        // -1: each combination's time.steps
};

struct SweepOutcome {
  std::size_t combinations = 0;
  int failed = 0;           // combinations whose run failed (their row says how)
  int worstExitCode = 0;    // 0, or the largest failed run's exit code (2 input, 3 numerical)
  int unconvergedRuns = 0;  // runs with steps that stopped above solver.pd_tolerance
  std::vector<std::string> failures;  // "combination K (PATH=v, ...) on rank R: message"
};

// The combinations in order, each as the overrides that make it (first axis slowest).
std::vector<std::vector<SceneOverride>> sweepCombinations(const SweepSettings& settings);

// Loads every combination's scene: a combination that is bad input is an InputError naming it.
// Call it before runSweep (and before processWorkers(), so that bad input never starts MPI).
void checkSweepCombinations(const SweepSettings& settings);

// Runs the combinations over `workers`; rank 0 writes `csvPath` atomically. A run that fails
// (numerical failure, a mesh the solver rejects) is a row with its error and counted in the
// outcome, not an exception.
SweepOutcome runSweep(const SweepSettings& settings, WorkDistributor& workers,
                      const std::string& csvPath);

}  // namespace weft
