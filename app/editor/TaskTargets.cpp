#include "TaskTargets.h"

#include <weft/core/Error.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/MeshReader.h>
#include <weft/scene/SceneLoader.h>

#include "ObjectPicking.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <unistd.h>

namespace weft::editor {

TaskTargets::TaskTargets(EditorDocument& document, const SimulationCache& cache,
                         const Selection& selection, ViewportFrame& viewport,
                         const render::Camera& camera)
    : document_(document),
      cache_(cache),
      selection_(selection),
      viewport_(viewport),
      camera_(camera) {}

std::string TaskTargets::writeTargets(const std::string& sceneFile) {
  const std::vector<FinalTarget> list = all();
  if (list.empty()) return "";
  const Scene* scene = document_.scene();
  if (!scene)
    return "the final targets were not written: the scene does not validate (save again once it "
           "does)";
  // Targets read from an opened scene are written only once edited (the scene then names the
  // editor's file); until then the scene's own file stays as it is.
  const std::string owned = ownedFinalTargetFile(document_.document(), document_.sidecar());
  if (owned.empty()) return "";
  // Written before a Save As renames it (EditorDocument::saveAs): under the name it will have.
  const std::string name = finalTargetFileAfterSaveAs(owned, document_.file(), sceneFile);
  const std::string directory = std::filesystem::absolute(sceneFile).parent_path().string();
  writeTargetNpy(resolveScenePath(directory, name),
                 finalTargetMatrix(list, document_.cloth()->rest.vertices));
  return "";
}

std::string TaskTargets::editTargets(const std::string& label, std::vector<FinalTarget> list,
                                     const std::string& coalesceKey) {
  const std::string file = finalTargetFileName(document_.file());
  return document_.editWithSidecar(
      label,
      [&](nlohmann::json& doc, nlohmann::json& sidecar) {
        setFinalTargets(doc, sidecar, list, file);
      },
      coalesceKey);
}

std::string TaskTargets::setTargetsFromSelection() {
  if (selection_.empty()) return "select the vertices to set targets for first";
  std::vector<FinalTarget> list = all();
  for (int node : selection_.nodes()) {
    const auto p = viewport_.shownPosition(node);
    if (!p) return "vertex " + std::to_string(node) + " is not a cloth vertex of the scene shown";
    bool found = false;
    for (FinalTarget& t : list)
      if (t.node == node) t.position = *p, found = true;
    if (!found) list.push_back({node, *p});
  }
  return editTargets("Set " + std::to_string(selection_.nodes().size()) + " targets",
                     std::move(list));
}

std::string TaskTargets::setTarget(int node, const Vec3& position, const std::string& coalesceKey) {
  if (!position.allFinite()) return "a target position must be finite";
  const Scene* scene = viewport_.lastValidScene().get();
  if (!scene || node < 0 || node >= scene->vertexCount())
    return "vertex " + std::to_string(node) + " is not a cloth vertex";
  std::vector<FinalTarget> list = all();
  bool found = false;
  for (FinalTarget& t : list)
    if (t.node == node) t.position = position, found = true;
  if (!found) list.push_back({node, position});
  return editTargets("Set target of vertex " + std::to_string(node), std::move(list), coalesceKey);
}

std::string TaskTargets::moveTargets(const std::vector<int>& nodes, const Vec3& delta,
                                     const std::string& coalesceKey) {
  if (!delta.allFinite()) return "the offset must be finite";
  std::vector<FinalTarget> list = all();
  int moved = 0;
  for (FinalTarget& t : list)
    if (std::find(nodes.begin(), nodes.end(), t.node) != nodes.end()) t.position += delta, ++moved;
  if (moved == 0) return "none of the selected vertices has a target";
  return editTargets("Move " + std::to_string(moved) + " targets", std::move(list), coalesceKey);
}

std::string TaskTargets::dragTargets(const std::vector<int>& nodes, float dx, float dy, int width,
                                     int height, const std::string& coalesceKey) {
  std::vector<FinalTarget> list = all();
  int moved = 0;
  for (FinalTarget& t : list) {
    if (std::find(nodes.begin(), nodes.end(), t.node) == nodes.end()) continue;
    // Move the target's projection by (dx, dy) at its own depth: unproject the moved pixel on
    // the plane through the target facing the camera.
    const auto pixel = projectToPixel(camera_, t.position.cast<float>(), width, height);
    if (!pixel) continue;
    const Ray ray = pixelRay(camera_, pixel->x() + dx, pixel->y() + dy, width, height);
    const Eigen::Vector3f normal = camera_.backward();
    const float denominator = ray.direction.dot(normal);
    if (std::abs(denominator) < 1e-8f) continue;
    const Eigen::Vector3f from = t.position.cast<float>();
    const float along = (from - ray.origin).dot(normal) / denominator;
    // Only the offset goes through single precision: untouched digits of the target stay.
    t.position += (ray.origin + along * ray.direction - from).cast<double>();
    ++moved;
  }
  if (moved == 0) return "none of the selected vertices has a target in view";
  return editTargets("Drag " + std::to_string(moved) + " targets", std::move(list), coalesceKey);
}

std::string TaskTargets::removeTargets(const std::vector<int>& nodes) {
  std::vector<FinalTarget> list = all(), kept;
  for (const FinalTarget& t : list)
    if (!nodes.empty() && std::find(nodes.begin(), nodes.end(), t.node) == nodes.end())
      kept.push_back(t);
  if (kept.size() == list.size())
    return list.empty() ? "there are no targets" : "none of these vertices has a target";
  return editTargets("Remove " + std::to_string(list.size() - kept.size()) + " targets",
                     std::move(kept));
}

std::string TaskTargets::loadTargetMotion(const std::string& file) {
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return file + ": file not found";
  const std::string path = documentRelativePath(file, document_.file(), document_.directory());
  // The engine's own check: a [states >= steps + 1, vertices, 3] array of finite numbers.
  try {
    Scene check = *scene;
    if (!check.task) check.task = Task{};
    check.task->loss = {{"trajectory", {{"target", path}}}};
    TaskLoss loss(check);
  } catch (const InputError& e) {
    return file + ": " + e.reason();
  } catch (const std::exception& e) {
    return file + ": " + e.what();
  }
  return setLossTerm("trajectory", {{"target", path}},
                     "Load target motion " + std::filesystem::path(file).filename().string());
}

std::string TaskTargets::loadTargetMesh(const std::string& file) {
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const std::string path = std::filesystem::absolute(file).string();
  const ClothModel& model = *document_.cloth();
  std::string counts;
  for (std::size_t c = 0; c < scene->cloths.size(); ++c) {
    const int n = scene->cloths[c].mesh.vertexCount();
    counts +=
        (c ? ", " : "") + std::string("cloth ") + std::to_string(c) + " has " + std::to_string(n);
    // The file in the cloth's place, placed by the loader as the cloth's own mesh is (its scale
    // and transform, the mesh checks): the scene as it would be with that mesh.
    nlohmann::json doc = document_.document();
    nlohmann::json& mesh = doc["cloths"][c]["mesh"];
    mesh.erase("grid");
    mesh["file"] = path;
    Scene placed;
    try {
      placed = parseScene(doc, document_.file(), document_.directory());
    } catch (const InputError& e) {
      if (e.path().rfind("cloths." + std::to_string(c) + ".mesh", 0) == 0)
        return file + ": " + e.reason();  // the file itself (missing, unreadable, degenerate)
      continue;  // another vertex count: the cloth's attachments or targets do not fit it
    }
    const TriangleMesh& shape = placed.cloths[c].mesh;
    if (shape.vertexCount() != n) continue;
    std::vector<FinalTarget> list;
    const int offset = model.vertexOffset[c];
    for (const FinalTarget& t : all())  // other cloths' targets stay
      if (t.node < offset || t.node >= offset + n) list.push_back(t);
    for (int v = 0; v < n; ++v) list.push_back({offset + v, shape.vertices.row(v).transpose()});
    return editTargets("Target shape " + std::filesystem::path(file).filename().string(),
                       std::move(list));
  }
  return file + ": " + std::to_string(readMesh(path).vertexCount()) + " vertices, but " + counts +
         " (a target shape has the garment's vertices, in its order)";
}

std::string TaskTargets::setHemline(double height) {
  if (!std::isfinite(height)) return "the hemline height must be a finite number";
  if (selection_.empty()) return "select the hemline's vertices first (e.g. the hem's border loop)";
  const std::vector<int> nodes = selection_.nodes();
  return setLossTerm("hemline", {{"vertices", nodes}, {"height", height}},
                     "Hemline of " + std::to_string(nodes.size()) + " vertices");
}

std::string TaskTargets::removeHemline() {
  return removeLossTerm("hemline", "Remove hemline", "hemline term");
}

std::string TaskTargets::removeTargetMotion() {
  return removeLossTerm("trajectory", "Remove target motion", "target motion");
}

std::string TaskTargets::setLossTerm(const std::string& term, const nlohmann::json& value,
                                     const std::string& label) {
  return document_.edit(label, [&](nlohmann::json& doc) {
    if (!doc.contains("task") || !doc["task"].is_object()) doc["task"] = nlohmann::json::object();
    if (!doc["task"].contains("loss") || !doc["task"]["loss"].is_object())
      doc["task"]["loss"] = nlohmann::json::object();
    doc["task"]["loss"][term] = value;
  });
}

std::string TaskTargets::removeLossTerm(const std::string& term, const std::string& label,
                                        const std::string& what) {
  if (!document_.find("task.loss." + term)) return "the task has no " + what;
  return document_.edit(label, [&](nlohmann::json& doc) {
    nlohmann::json& task = doc["task"];
    task["loss"].erase(term);
    // No term left: no task (a task needs a loss), unless it still names parameters.
    if (task["loss"].empty() && (!task.contains("parameters") || task["parameters"].empty()))
      doc.erase("task");
  });
}

const LossValue& TaskTargets::liveLoss() {
  return liveLoss_.evaluate(document_, cache_);
}

std::string TaskTargets::withHeldTargets(const std::function<std::string(const Scene&)>& use) {
  if (!document_.valid()) return "the scene does not validate: " + document_.validationError();
  nlohmann::json doc = document_.document();
  const std::vector<FinalTarget> list = all();
  std::string temporary;
  if (!list.empty()) {
    // The engine's TaskLoss reads targets from a file: targets not saved yet go to a private
    // temporary one, read once while `use` builds the loss and removed then.
    std::string name =
        (std::filesystem::temp_directory_path() / "weft-editor-target-XXXXXX").string();
    const int fd = ::mkstemp(name.data());
    if (fd < 0) return "cannot create a temporary target file";
    ::close(fd);
    temporary = name;
    try {
      writeTargetNpy(temporary, finalTargetMatrix(list, document_.cloth()->rest.vertices));
    } catch (const std::exception& e) {
      ::unlink(temporary.c_str());
      return e.what();
    }
    doc["task"]["loss"]["final"]["target"] = temporary;
  }
  std::string error;
  try {
    const Scene scene =
        parseScene(doc, document_.file().empty() ? document_.displayName() : document_.file(),
                   document_.directory());
    error = use(scene);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!temporary.empty()) ::unlink(temporary.c_str());
  return error;
}

}  // namespace weft::editor
