#include "ScenePathRebase.h"

#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <filesystem>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;

// A folder as one comparable absolute path ("/a/b/" and "/a/./b" are "/a/b").
fs::path folder(const std::string& directory) {
  fs::path p = fs::absolute(directory.empty() ? "." : directory).lexically_normal();
  if (p.has_parent_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

}  // namespace

std::vector<std::string> sceneFileReferences(const nlohmann::json& document) {
  std::vector<std::string> out;
  auto add = [&](const std::string& path) {
    const nlohmann::json* value = findJsonPath(document, path);
    if (value && value->is_string()) out.push_back(path);
  };
  auto count = [&](const std::string& path) -> std::size_t {
    const nlohmann::json* list = findJsonPath(document, path);
    return list && list->is_array() ? list->size() : 0;
  };
  for (const char* list : {"cloths", "obstacles"})
    for (std::size_t i = 0; i < count(list); ++i)
      add(std::string(list) + "." + std::to_string(i) + ".mesh.file");
  add("task.loss.trajectory.target");
  add("task.loss.final.target");
  for (std::size_t i = 0; i < count("task.loss.keypoints.points"); ++i)
    add("task.loss.keypoints.points." + std::to_string(i) + ".target");
  return out;
}

std::vector<std::string> rebaseSceneFiles(nlohmann::json& document,
                                          const std::string& fromDirectory,
                                          const std::string& toDirectory,
                                          const std::vector<std::string>& keep) {
  std::vector<std::string> changed;
  const fs::path from = folder(fromDirectory), to = folder(toDirectory);
  // Same folder: every reference still names its file, and is left exactly as written.
  if (from == to) return changed;
  for (const std::string& path : sceneFileReferences(document)) {
    if (std::find(keep.begin(), keep.end(), path) != keep.end()) continue;
    nlohmann::json& value = *findJsonPath(document, path);
    const std::string written = value.get<std::string>();
    if (written.empty() || fs::path(written).is_absolute()) continue;
    // The file the loader opens today, including its fallback to the working directory for a
    // reference not found beside the scene (so a CWD-relative reference becomes folder-relative).
    const fs::path file = fs::absolute(resolveScenePath(from.string(), written)).lexically_normal();
    // A reference to no file names nothing from either folder: it is kept as written, which is
    // what it usually means (a target a run will write beside the scene; a document built before
    // its first save, which names files relative to where it is saved).
    std::error_code ec;
    if (!fs::exists(file, ec)) continue;
    const fs::path relative = file.lexically_relative(to);
    // No relative path between them (not on POSIX, where both are under "/"): name it absolutely.
    const std::string rebased =
        relative.empty() ? file.generic_string() : relative.generic_string();
    if (rebased == written) continue;
    value = rebased;
    changed.push_back(path);
  }
  return changed;
}

}  // namespace weft::editor
