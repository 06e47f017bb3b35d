#pragma once
// `weft bench continuity` (ContinuityBench.cpp): DiffCloth's Fig. 2, node speeds of a cloth on a
// frictional sphere against the friction coefficient, analytic sphere against triangulated.

#include <string>

namespace weft::bench {

struct ContinuityBenchOptions {
  bool quick = false;
  std::string scene;               // empty: assets/scenes/sphere.json
  int threads = 1;                 // OpenMP threads
  std::string contact = "newton";  // one of kContactSolves (ContactBench.h)
  int subdivisions = 2;            // the triangulated sphere's (0..5)
  int resolution = 0;              // the cloth's quads per side; 0: the scene's grid
};

// Writes the tables into `outDir` (staged); returns the exit code.
int runContinuityBench(const ContinuityBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
