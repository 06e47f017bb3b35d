#pragma once
// `weft bench forward` (ForwardBench.cpp): seconds per step and trajectory error of the hanging
// cloth in wind against a tightly converged reference, over the PD iteration cap and tolerance,
// and PD iterations with and without Anderson acceleration.

#include <string>
#include <vector>

namespace weft::bench {

struct ForwardBenchOptions {
  bool quick = false;
  std::string scene;             // empty: assets/scenes/wind.json
  int threads = 1;               // OpenMP threads
  std::vector<int> resolutions;  // quads per side; empty: 12, 24, 48, 96 (quick: 12, 24)
};

// Writes the tables into `outDir` (staged); returns the exit code.
int runForwardBench(const ForwardBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
