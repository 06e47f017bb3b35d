#pragma once
// `weft bench soak` (SoakBench.cpp): long runs that would show a leak or a slow drift. A cloth
// draped on a sphere with self-collision, stepped for a long time, and an optimiser run for many
// evaluations, each sampling the process's resident memory and the time per step or per
// evaluation as it goes.

#include <string>
#include <vector>

namespace weft::bench {

struct SoakBenchOptions {
  bool quick = false;
  int threads = 1;      // OpenMP threads
  int steps = 0;        // of the contact scene; 0: 100,000 (quick: 100)
  int evaluations = 0;  // of the optimiser; 0: 500 (quick: 20)
};

// One sample of a soak run: after `end` steps or evaluations, the mean wall milliseconds per
// step or evaluation since the previous sample, and the resident memory (VmRSS, MB).
struct SoakWindow {
  long long end = 0;
  double msPerUnit = 0.0;
  double rssMb = 0.0;
};

// Resident memory may grow by this much after the warm-up (allocator noise of a process that
// frees and reallocates; a leak of one 625-node matrix per step exceeds it within 600 steps).
inline constexpr double kSoakMemoryGrowthLimitMb = 8.0;
// The mean time of the last tenth of the windows may exceed the first tenth's after the warm-up
// by this factor (another process on the machine moves single windows by more, a tenth of them
// far less).
inline constexpr double kSoakTimeDriftLimit = 1.25;

// What a soak run's samples say. The warm-up is the first tenth of the windows (at least one):
// the first factorisations and buffers growing to their working size.
struct SoakJudgement {
  double warmupRssMb = 0.0;  // at the warm-up's last window
  double endRssMb = 0.0;     // at the last window
  double growthMb = 0.0;     // endRssMb - warmupRssMb
  double firstMs = 0.0;      // mean ms per unit, the first tenth of the windows after the warm-up
  double lastMs = 0.0;       // mean ms per unit, the last tenth
  double drift = 1.0;        // lastMs / firstMs
  bool memoryGrew = false;   // growthMb > kSoakMemoryGrowthLimitMb
  bool timeDrifted = false;  // drift > kSoakTimeDriftLimit
};
SoakJudgement judgeSoak(const std::vector<SoakWindow>& windows);

// Writes soak.csv, soak.md and soak.png into `outDir` (staged); returns the exit code: 0, or 1
// when memory grew or time per step drifted beyond the limits soak.md states.
int runSoakBench(const SoakBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
