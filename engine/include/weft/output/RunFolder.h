#pragma once
// A folder written by `weft simulate` (RunWriter.h, beside it: the writer and the reader of one
// format), read back for rendering: the scene as simulated, every state, and per-node contact
// data when the run recorded it.

#include <weft/core/Types.h>
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
  ContactRecord contacts;
};

// True when `path` is a folder (a run) rather than a scene file.
bool isRunFolder(const std::string& path);

// Throws InputError naming the file and what is missing or inconsistent.
RunFolder loadRunFolder(const std::string& path);

}  // namespace weft
