#pragma once
// `weft bench contact` (ContactBench.cpp): seconds per step split by module, contact cost
// against the number of contacts, and peak memory, for the Sphere, Slope and Crumple scenes.

#include <string>
#include <vector>

namespace weft::bench {

// The scenes the benchmark knows, by the names --scenes takes.
inline const std::vector<std::string> kContactBenchScenes = {"sphere", "slope", "crumple"};
// The contact solves --contact takes ("scene": each scene's own solver.contact); "-whole": with
// adaptive time stepping off (solver.max_halvings 0), every step solved whole, as before it.
inline const std::vector<std::string> kContactSolves = {
    "scene", "pd", "newton", "active_set", "pd-whole", "newton-whole", "active_set-whole"};

struct ContactBenchOptions {
  bool quick = false;
  int threads = 1;                    // OpenMP threads
  std::vector<std::string> scenes;    // of kContactBenchScenes; empty: all three
  std::vector<int> resolutions;       // quads per side; empty: 24, 48, 96 (quick: 8, 16)
  std::vector<std::string> contacts;  // of kContactSolves; empty: "scene"
};

// Writes the tables into `outDir` (staged); returns the exit code.
int runContactBench(const ContactBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
