#pragma once
// A folder written by `weft simulate` (RunWriter.h, beside it: the writer and the reader of one
// format), read back for rendering: the scene as simulated, every state, and per-node contact
// data when the run recorded it.

#include <weft/core/Types.h>
#include <weft/record/StepStats.h>
#include <weft/scene/Scene.h>

#include <cstdint>
#include <string>
#include <vector>

namespace weft {

// Per state and node: the contact branch (0 none, 1 take-off, 2 stick, 3 slip) and the contact
// force (N). Read from contact_branches.npy [states, nodes] and contact_forces.npy
// [states, nodes, 3] when a run has them; empty otherwise.
struct ContactRecord {
  std::vector<std::vector<std::uint8_t>> branches;
  std::vector<NodeMatrix> forces;
  bool empty() const { return branches.empty(); }
};

struct RunFolder {
  std::string path;
  Scene scene;
  std::vector<NodeMatrix> states;  // positions.npy: states 0..steps
  // velocities.npy [states, nodes, 3] (m/s) when the run has it (the editor's saved runs do;
  // `weft simulate` does not write it); empty otherwise.
  std::vector<NodeMatrix> velocities;
  // stats.csv, one row per step (steps 1..states-1), read by column name; module times are not
  // read back (moduleSeconds stays empty). Empty when the run has no stats.csv.
  std::vector<StepStats> steps;
  ContactRecord contacts;
};

// True when `path` is a folder (a run) rather than a scene file.
bool isRunFolder(const std::string& path);

// Throws InputError naming the file and what is missing or inconsistent.
RunFolder loadRunFolder(const std::string& path);

}  // namespace weft
