#pragma once
// `weft bench backward` (BackwardBench.cpp): DiffCloth Table 1, the backward pass of a
// trajectory loss timed with each adjoint solver at several resolutions; --calibrate measures
// the cost of a factorisation instead.

#include <string>
#include <vector>

namespace weft::bench {

// The scenes the benchmark knows, by the names --scenes takes.
inline const std::vector<std::string> kBackwardBenchScenes = {"wind", "wind_reference", "slope"};

struct BackwardBenchOptions {
  bool quick = false;
  std::vector<std::string> scenes;  // of kBackwardBenchScenes; empty: wind, slope
  int threads = 1;                  // OpenMP threads
  std::vector<int> resolutions;     // quads per side; empty: 12, 24, 48 (quick: 12, 24)
  bool calibrate = false;
};

// The scale of the adjoint's factorisation-cost estimate (AdjointSystem::hessianFactorCost, in
// GMRES iterations: this scale times the square root of H's factor flops over P's), which
// --calibrate's estimated_iterations column uses.
double factorCostScale();

// Writes the tables into `outDir` (staged); returns the exit code.
int runBackwardBench(const BackwardBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
