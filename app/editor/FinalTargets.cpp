#include "FinalTargets.h"

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

namespace weft::editor {

namespace fs = std::filesystem;

std::vector<FinalTarget> finalTargets(const nlohmann::json& sidecar) {
  std::vector<FinalTarget> out;
  if (!sidecar.is_object() || !sidecar.contains("final_targets")) return out;
  const nlohmann::json& positions =
      sidecar["final_targets"].value("positions", nlohmann::json::object());
  for (auto it = positions.begin(); it != positions.end(); ++it) {
    FinalTarget t;
    t.node = std::stoi(it.key());
    for (int c = 0; c < 3; ++c) t.position[c] = it.value().at(std::size_t(c)).get<double>();
    out.push_back(t);
  }
  std::sort(out.begin(), out.end(),
            [](const FinalTarget& a, const FinalTarget& b) { return a.node < b.node; });
  return out;
}

std::string finalTargetFileName(const std::string& sceneFile) {
  const std::string stem = sceneFile.empty() ? "untitled" : fs::path(sceneFile).stem().string();
  return stem + "-final-target.npy";
}

std::string finalTargetFileAfterSaveAs(const std::string& name, const std::string& oldScene,
                                       const std::string& newScene) {
  return name == finalTargetFileName(oldScene) ? finalTargetFileName(newScene) : name;
}

void renameFinalTargetFile(nlohmann::json& document, nlohmann::json& sidecar,
                           const std::string& oldScene, const std::string& newScene) {
  if (!sidecar.contains("final_targets") || !sidecar["final_targets"].is_object()) return;
  nlohmann::json& file = sidecar["final_targets"]["file"];
  if (!file.is_string()) return;
  const std::string renamed =
      finalTargetFileAfterSaveAs(file.get<std::string>(), oldScene, newScene);
  nlohmann::json* named = findJsonPath(document, "task.loss.final.target");
  if (named && *named == file) *named = renamed;
  file = renamed;
}

std::string ownedFinalTargetFile(const nlohmann::json& document, const nlohmann::json& sidecar) {
  if (finalTargets(sidecar).empty()) return "";
  const nlohmann::json& file = sidecar["final_targets"].value("file", nlohmann::json());
  const nlohmann::json* named = findJsonPath(document, "task.loss.final.target");
  if (!file.is_string() || !named || *named != file) return "";
  return file.get<std::string>();
}

void setFinalTargets(nlohmann::json& document, nlohmann::json& sidecar,
                     std::vector<FinalTarget> targets, const std::string& fileName) {
  std::sort(targets.begin(), targets.end(),
            [](const FinalTarget& a, const FinalTarget& b) { return a.node < b.node; });
  targets.erase(
      std::unique(targets.begin(), targets.end(),
                  [](const FinalTarget& a, const FinalTarget& b) { return a.node == b.node; }),
      targets.end());
  if (targets.empty()) {
    sidecar.erase("final_targets");
    if (!document.contains("task") || !document["task"].is_object()) return;
    nlohmann::json& task = document["task"];
    if (task.contains("loss") && task["loss"].is_object()) task["loss"].erase("final");
    const bool noLoss =
        !task.contains("loss") || (task["loss"].is_object() && task["loss"].empty());
    const bool noParameters = !task.contains("parameters") || task["parameters"].empty();
    // A task without a loss is invalid; one that has nothing else either goes with its last term.
    if (noLoss && noParameters) document.erase("task");
    return;
  }
  std::string file = fileName;
  if (sidecar.contains("final_targets")) file = sidecar["final_targets"].value("file", fileName);
  nlohmann::json positions = nlohmann::json::object();
  std::vector<int> vertices;
  for (const FinalTarget& t : targets) {
    positions[std::to_string(t.node)] = {t.position.x(), t.position.y(), t.position.z()};
    vertices.push_back(t.node);
  }
  sidecar["final_targets"] = {{"file", file}, {"positions", positions}};
  if (!document.contains("task") || !document["task"].is_object())
    document["task"] = nlohmann::json::object();
  nlohmann::json& task = document["task"];
  if (!task.contains("loss") || !task["loss"].is_object()) task["loss"] = nlohmann::json::object();
  nlohmann::json term = {{"target", file}, {"vertices", vertices}};
  const nlohmann::json& loss = task["loss"];
  if (loss.contains("final") && loss["final"].is_object() && loss["final"].contains("weight"))
    term["weight"] = loss["final"]["weight"];
  task["loss"]["final"] = term;
}

nlohmann::json readFinalTargets(const Scene& scene) {
  if (!scene.task || !scene.task->loss.contains("final")) return nlohmann::json::object();
  const nlohmann::json& term = scene.task->loss["final"];
  if (!term.contains("vertices") || !term["vertices"].is_array()) return nlohmann::json::object();
  try {
    const std::string path =
        resolveScenePath(scene.directory, term.at("target").get<std::string>());
    const NpyArray a = readNpy(path);
    const std::size_t nodes = static_cast<std::size_t>(scene.vertexCount());
    std::size_t first = 0;  // offset of the last state
    if (a.shape.size() == 3 && a.shape[1] == nodes && a.shape[2] == 3)
      first = (a.shape[0] - 1) * nodes * 3;
    else if (!(a.shape.size() == 2 && a.shape[0] == nodes && a.shape[1] == 3))
      return nlohmann::json::object();
    if (a.data.size() < first + nodes * 3) return nlohmann::json::object();
    nlohmann::json positions = nlohmann::json::object();
    for (const nlohmann::json& v : term["vertices"]) {
      const long long node = v.get<long long>();
      if (node < 0 || node >= static_cast<long long>(nodes)) return nlohmann::json::object();
      const double* p = &a.data[first + std::size_t(node) * 3];
      positions[std::to_string(node)] = {p[0], p[1], p[2]};
    }
    // The loaded targets are edited from now on, but written to the editor's own file: the one
    // read may be shared (a recorded run).
    return {
        {"final_targets", {{"file", finalTargetFileName(scene.file)}, {"positions", positions}}}};
  } catch (const std::exception&) {
    return nlohmann::json::object();  // shown from the file (or its warning) as before
  }
}

NodeMatrix finalTargetMatrix(const std::vector<FinalTarget>& targets, const NodeMatrix& rest) {
  NodeMatrix out = rest;
  for (const FinalTarget& t : targets)
    if (t.node >= 0 && t.node < out.rows()) out.row(t.node) = t.position.transpose();
  return out;
}

void writeTargetNpy(const std::string& path, const NodeMatrix& target) {
  std::vector<double> flat(static_cast<std::size_t>(target.rows()) * 3);
  for (Eigen::Index i = 0; i < target.rows(); ++i)
    for (int c = 0; c < 3; ++c) flat[std::size_t(i) * 3 + std::size_t(c)] = target(i, c);
  const fs::path final = fs::absolute(path);
  std::error_code ec;
  if (!fs::is_directory(final.parent_path(), ec))
    throw InputError(path, "-", "the folder does not exist");
  std::string temp =
      (final.parent_path() / ("." + final.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0)
    throw InputError(path, "-",
                     "cannot create a temporary file: " + std::string(std::strerror(errno)));
  ::close(fd);
  try {
    writeNpy(temp, {static_cast<std::size_t>(target.rows()), 3}, flat.data());
  } catch (...) {
    ::unlink(temp.c_str());
    throw;
  }
  ::chmod(temp.c_str(), 0644);  // mkstemp makes 0600; a target is an ordinary data file
  if (::rename(temp.c_str(), final.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temp.c_str());
    throw InputError(path, "-", "cannot replace the file: " + reason);
  }
}

}  // namespace weft::editor
