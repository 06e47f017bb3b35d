#pragma once
// Writes a simulated run in the `weft simulate` contract: positions.npy, stats.csv, rest.obj
// and summary.json (plus scene.json, the scene as simulated; summary.json's scene_directory
// resolves its relative paths), into a folder (normally a StagedDirectory, so nothing partial is
// left). RunFolder.h reads it back.

#include <weft/model/ClothModel.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft {

struct RunSummary {
  double seconds = 0.0;  // wall time of the simulation
  std::vector<std::string> moduleNames;
  std::vector<double> moduleSeconds;  // totals, aligned with moduleNames
  int threads = 1;
};

// Peak resident memory of this process so far (MB).
double peakMemoryMegabytes();
nlohmann::json summarize(const Scene& scene, const Trajectory& trajectory, const RunSummary& run);
void writeRun(const std::string& folder, const Scene& scene, const ClothModel& model,
              const Trajectory& trajectory, const RunSummary& run);

}  // namespace weft
