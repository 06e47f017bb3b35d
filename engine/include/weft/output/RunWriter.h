#pragma once
// Writes a simulated run in the `weft simulate` contract: positions.npy, stats.csv, rest.obj
// and summary.json (plus scene.json, the scene as simulated; summary.json's scene_directory
// resolves its relative paths, and contact_branches.npy / contact_forces.npy for contact
// scenes), into a folder (normally a StagedDirectory, so nothing partial is left). RunFolder.h
// reads it back.
//
// The run is written as it is simulated, one state at a time: the arrays go to their files as
// they come and only the per-step statistics are kept, so memory does not grow with the states
// and contacts of the run (a Trajectory holds every state, velocity and contact record).

#include <weft/io/Npy.h>
#include <weft/model/ClothModel.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>
#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace weft {
namespace collision {
class MeshCrossingCheck;
}

struct RunSummary {
  double seconds = 0.0;  // wall time of the simulation
  std::vector<std::string> moduleNames;
  std::vector<double> moduleSeconds;  // totals, aligned with moduleNames
  int threads = 1;
};

// Peak resident memory of this process so far (MB).
double peakMemoryMegabytes();

class RunWriter {
 public:
  // A run of `steps` steps of `model`'s nodes; `contactArrays` writes the per-state contact
  // branches and forces (contact scenes with at least one step).
  RunWriter(std::string folder, const Scene& scene, const ClothModel& model, int steps,
            bool contactArrays);
  ~RunWriter();
  // State 0, then after every step its state, statistics and (contact scenes) contacts.
  void addInitialState(const NodeMatrix& x);
  void addStep(const NodeMatrix& x, const StepStats& stats, const StepContacts* contacts);
  // After the last step: stats.csv, rest.obj, scene.json and summary.json; checks the counts.
  void finish(const RunSummary& run);

  const std::vector<StepStats>& steps() const { return steps_; }

 private:
  void addPositions(const NodeMatrix& x);

  std::string folder_;
  const Scene& scene_;
  const ClothModel& model_;
  std::size_t nodes_;
  double restArea_;
  NpyWriter positions_;
  std::optional<NpyWriter> branches_, forces_;
  // One state's rows, reused: no allocation per step.
  std::vector<double> row_, branchRow_, forceRow_, strength_;
  std::vector<double> areaRatio_;  // per state
  std::vector<StepStats> steps_;
  // Scenes with self-collision: edge-triangle crossings of the self-colliding cloths per state.
  std::unique_ptr<collision::MeshCrossingCheck> crossingCheck_;
  std::vector<int> crossings_;
};

// summary.json's fields that depend on the steps only (not area_ratio, which RunWriter adds).
nlohmann::json summarize(const Scene& scene, int vertices, const std::vector<StepStats>& steps,
                         const RunSummary& run);

}  // namespace weft
