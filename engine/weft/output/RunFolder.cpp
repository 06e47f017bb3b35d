#include <weft/output/RunFolder.h>

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

nlohmann::json readJson(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "RUNDIR", "missing: not a folder written by weft simulate");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "json", e.what());
  }
}

}  // namespace

bool isRunFolder(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

RunFolder loadRunFolder(const std::string& path) {
  RunFolder run;
  run.path = path;
  const std::string summaryFile = path + "/summary.json", sceneFile = path + "/scene.json",
                    positionsFile = path + "/positions.npy";
  const nlohmann::json summary = readJson(summaryFile);
  // Relative mesh and target paths in scene.json are relative to the original scene's folder.
  std::string directory = path;
  if (summary.contains("scene_directory") && summary["scene_directory"].is_string())
    directory = summary["scene_directory"].get<std::string>();
  run.scene = parseScene(readJson(sceneFile), sceneFile, directory);

  if (!fs::exists(positionsFile))
    throw InputError(positionsFile, "RUNDIR", "missing: not a folder written by weft simulate");
  const NpyArray positions = readNpy(positionsFile);
  const std::size_t nodes = static_cast<std::size_t>(run.scene.vertexCount());
  if (positions.shape.size() != 3 || positions.shape[1] != nodes || positions.shape[2] != 3 ||
      positions.shape[0] < 1)
    throw InputError(positionsFile, "shape",
                     "expected [states, " + std::to_string(nodes) + ", 3] for the scene's " +
                         std::to_string(nodes) + " vertices");
  const std::size_t states = positions.shape[0];
  run.states.assign(states, NodeMatrix(Eigen::Index(nodes), 3));
  for (std::size_t s = 0; s < states; ++s)
    for (std::size_t i = 0; i < nodes; ++i)
      for (int c = 0; c < 3; ++c)
        run.states[s](Eigen::Index(i), c) = positions.data[(s * nodes + i) * 3 + std::size_t(c)];

  const std::string branchesFile = path + "/contact_branches.npy",
                    forcesFile = path + "/contact_forces.npy";
  if (fs::exists(branchesFile)) {
    const NpyArray b = readNpy(branchesFile);
    if (b.shape.size() != 2 || b.shape[0] != states || b.shape[1] != nodes)
      throw InputError(branchesFile, "shape",
                       "expected [" + std::to_string(states) + ", " + std::to_string(nodes) + "]");
    run.contacts.branches.assign(states, std::vector<std::uint8_t>(nodes, 0));
    for (std::size_t s = 0; s < states; ++s)
      for (std::size_t i = 0; i < nodes; ++i) {
        const double v = b.data[s * nodes + i];
        if (!(v >= 0.0 && v <= 3.0 && v == double(int(v))))
          throw InputError(branchesFile, "value",
                           "branch ids are 0 (none), 1 (take-off), 2 (stick) or 3 (slip)");
        run.contacts.branches[s][i] = static_cast<std::uint8_t>(v);
      }
    if (fs::exists(forcesFile)) {
      const NpyArray f = readNpy(forcesFile);
      if (f.shape.size() != 3 || f.shape[0] != states || f.shape[1] != nodes || f.shape[2] != 3)
        throw InputError(
            forcesFile, "shape",
            "expected [" + std::to_string(states) + ", " + std::to_string(nodes) + ", 3]");
      run.contacts.forces.assign(states, NodeMatrix(Eigen::Index(nodes), 3));
      for (std::size_t s = 0; s < states; ++s)
        for (std::size_t i = 0; i < nodes; ++i)
          for (int c = 0; c < 3; ++c)
            run.contacts.forces[s](Eigen::Index(i), c) =
                f.data[(s * nodes + i) * 3 + std::size_t(c)];
    }
  }
  return run;
}

}  // namespace weft
