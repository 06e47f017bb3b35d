#include "EditorSession.h"

#include <FrameBuilder.h>

#include "ObstacleTemplates.h"

#include <weft/core/Error.h>
#include <weft/diff/TaskLoss.h>
#include <weft/render/Bounds.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

namespace weft::editor {

EditorSession::EditorSession(const std::string& recentStore) : recent_(recentStore) {
  lastValidScene_ = document_.sharedScene();
  frameCamera(16.0f / 9.0f);
}

EditorSession::~EditorSession() = default;

void EditorSession::newDocument(nlohmann::json document) {
  cache_.clear();
  document_ = EditorDocument(std::move(document));
  afterDocumentReplaced();
}

void EditorSession::open(const std::string& file) {
  EditorDocument opened;
  opened.open(file);  // throws, leaving the current document as it was
  cache_.clear();
  document_ = std::move(opened);
  recent_.add(file);
  afterDocumentReplaced();
}

void EditorSession::afterDocumentReplaced() {
  // Final targets of an opened scene become editable (their positions come from its .npy).
  if (const Scene* scene = document_.scene()) document_.resetSidecar(readFinalTargets(*scene));
  selection_.clear();
  playback_ = Playback();
  documentBuilder_.reset();
  cacheBuilder_.reset();
  lastValidScene_ = document_.sharedScene();
  frameCamera(16.0f / 9.0f);
}

std::string EditorSession::writeTargets(const std::string& sceneFile) {
  const std::vector<FinalTarget> list = targets();
  if (list.empty()) return "";
  const Scene* scene = document_.scene();
  if (!scene)
    return "the final targets were not written: the scene does not validate (save again once it does)";
  const std::string name = document_.sidecar()["final_targets"].value("file", finalTargetFileName(sceneFile));
  // Targets read from an opened scene are written only once edited (the scene then names the
  // editor's file); until then the scene's own file stays as it is.
  const nlohmann::json* named = document_.find("task.loss.final.target");
  if (!named || !named->is_string() || named->get<std::string>() != name) return "";
  const std::string directory = std::filesystem::absolute(sceneFile).parent_path().string();
  writeTargetNpy(resolveScenePath(directory, name), finalTargetMatrix(list, buildClothModel(*scene).rest.vertices));
  return "";
}

std::string EditorSession::save() {
  if (document_.file().empty()) throw InputError("untitled", "-", "the document has no file yet: use Save As");
  const std::string warning = writeTargets(document_.file());
  document_.save();
  recent_.add(document_.file());
  return warning;
}

std::string EditorSession::saveAs(const std::string& file) {
  if (file.empty()) throw InputError("-", "-", "no file name given");
  const std::string warning = writeTargets(file);
  document_.saveAs(file);
  recent_.add(file);
  return warning;
}

MeshImport EditorSession::previewGarment(const MeshImportOptions& options) const {
  return prepareGarment(options, document_.file(), document_.directory());
}

std::string EditorSession::importGarment(const MeshImportOptions& options) {
  const MeshImport prepared = previewGarment(options);
  if (!prepared.ok()) return prepared.error;
  const std::string name = std::filesystem::path(options.file).filename().string();
  return document_.edit("Import garment " + name, [&](nlohmann::json& doc) {
    if (!doc.contains("cloths") || !doc["cloths"].is_array()) doc["cloths"] = nlohmann::json::array();
    doc["cloths"].push_back(prepared.entry);
  });
}

std::string EditorSession::addObstacle(const std::string& shape) {
  nlohmann::json obstacle;
  try {
    obstacle = defaultObstacle(shape);
  } catch (const std::exception& e) {
    return e.what();
  }
  return document_.edit("Add " + shape, [&](nlohmann::json& doc) {
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array()) doc["obstacles"] = nlohmann::json::array();
    doc["obstacles"].push_back(obstacle);
  });
}

std::string EditorSession::importMeshObstacle(const MeshImportOptions& options) {
  const MeshImport prepared = prepareMeshObstacle(options, document_.file(), document_.directory());
  if (!prepared.ok()) return prepared.error;
  const std::string name = std::filesystem::path(options.file).filename().string();
  return document_.edit("Add mesh obstacle " + name, [&](nlohmann::json& doc) {
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array()) doc["obstacles"] = nlohmann::json::array();
    doc["obstacles"].push_back(prepared.entry);
  });
}

std::string EditorSession::simulate(int steps) {
  auto scene = document_.sharedScene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  cache_.start(scene, steps >= 0 ? steps : scene->time.steps);
  playback_.scrub(0, 1);
  return "";
}

int EditorSession::availableFrames() const { return cache_.frameCount(); }

std::string EditorSession::selectNodes(const std::vector<int>& nodes, bool add) {
  const Scene* scene = lastValidScene_.get();
  const int count = scene ? scene->vertexCount() : 0;
  for (int n : nodes)
    if (n < 0 || n >= count)
      return "vertex " + std::to_string(n) + " is not a cloth vertex (the scene has " +
             std::to_string(count) + ")";
  if (add)
    selection_.add(nodes);
  else
    selection_.set(nodes);
  return "";
}

std::optional<int> EditorSession::clickSelect(float x, float y, int width, int height, bool add) {
  const render::RenderScene* scene = viewportScene();
  if (!scene) return std::nullopt;
  const auto vertex = pickVertex(scene->cloth, pixelRay(camera_, x, y, width, height));
  if (!add) selection_.clear();
  if (vertex) {
    if (add)
      selection_.toggle(*vertex);
    else
      selection_.set({*vertex});
  }
  return vertex;
}

void EditorSession::boxSelectPixels(float x0, float y0, float x1, float y1, int width, int height,
                                    bool add) {
  const render::RenderScene* scene = viewportScene();
  if (!scene) return;
  const auto inside = boxSelect(scene->cloth, camera_, {x0, y0}, {x1, y1}, width, height);
  if (add)
    selection_.add(inside);
  else
    selection_.set(inside);
}

std::string EditorSession::pinSelection() {
  if (selection_.empty()) return "nothing is selected";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel model = buildClothModel(*scene);
  const std::vector<int> nodes = selection_.nodes();
  return document_.edit("Pin " + std::to_string(nodes.size()) + " vertices", [&](nlohmann::json& doc) {
    addFixedAttachments(doc, nodes, model.vertexOffset);
  });
}

void EditorSession::frameCamera(float aspect, render::NamedView view) {
  const render::RenderScene* scene = viewportScene();
  render::Bounds bounds;
  if (scene) bounds = render::sceneBounds(*scene);
  if (bounds.empty()) bounds.extend(render::Vec3f(-1, -1, -1)), bounds.extend(render::Vec3f(1, 1, 1));
  camera_ = render::namedViewCamera(view, bounds, aspect);
}

EditorSession::Builder* EditorSession::builderFor(const std::shared_ptr<const Scene>& scene,
                                                  std::unique_ptr<Builder>& slot) {
  if (!scene) return nullptr;
  if (!slot || slot->scene != scene) {
    auto b = std::make_unique<Builder>();
    b->scene = scene;
    b->model = buildClothModel(*scene);
    b->frames = std::make_unique<FrameBuilder>(*scene, b->model);
    slot = std::move(b);
  }
  return slot.get();
}

void EditorSession::tick(double seconds) {
  const int available = cache_.frameCount();
  const Scene* scene = cache_.scene().get();
  playback_.advance(seconds, scene ? scene->time.dt : 0.01, available, cache_.running());
  if (playback_.frame() >= available) playback_.scrub(playback_.frame(), available);
  stepSeries_.update(cache_);
}

const render::RenderScene* EditorSession::viewportScene() {
  if (document_.valid()) lastValidScene_ = document_.sharedScene();
  const std::shared_ptr<const Scene> cached = cache_.scene();
  const int available = cache_.frameCount();
  // Cached states are shown while they fit the mesh being edited (same node count), even when
  // stale: the timeline then says so.
  showingCache_ = cached && available > 0 &&
                  (!lastValidScene_ || lastValidScene_->vertexCount() == cached->vertexCount());
  FrameKey key;
  key.scene = showingCache_ ? static_cast<const void*>(cached.get()) : lastValidScene_.get();
  key.revision = document_.revision();
  key.runId = showingCache_ ? cache_.runId() : -1;
  key.frame = showingCache_ ? std::min(playback_.frame(), available - 1) : -1;
  key.colours = contactColours;
  key.arrows = forceArrows;
  if (frameValid_ && key == frameKey_) return &frame_;
  frameValid_ = false;
  ++frameVersion_;
  try {
    if (showingCache_) {
      Builder* b = builderFor(cached, cacheBuilder_);
      const auto f = cache_.frame(key.frame);
      frame_ = b->frames->frame(f->positions, f->state);
      const int nodes = static_cast<int>(f->positions.rows());
      if (!f->branches.empty() && (contactColours || forceArrows)) {
        render::ContactOverlay overlay;
        overlay.branches.assign(static_cast<std::size_t>(nodes), render::ContactBranch::None);
        if (contactColours)
          for (std::size_t i = 0; i < f->branches.size() && i < overlay.branches.size(); ++i)
            overlay.branches[i] = static_cast<render::ContactBranch>(f->branches[i]);
        if (forceArrows) {
          const std::vector<Vec3> forces = nodeContactForces(f->contacts, nodes, cached->time.dt);
          overlay.forces.reserve(forces.size());
          for (const Vec3& force : forces) overlay.forces.push_back(force.cast<float>());
        }
        frame_.contacts = std::move(overlay);
      }
    } else {
      Builder* b = builderFor(lastValidScene_, documentBuilder_);
      if (!b) return nullptr;
      frame_ = b->frames->frame(b->model.rest.vertices, 0);
    }
    // Targets the editor holds replace the ones the frame builder read from the scene's file.
    const std::vector<FinalTarget> list = targets();
    if (!list.empty()) {
      frame_.targetPoints.clear();
      for (const FinalTarget& t : list) frame_.targetPoints.push_back(t.position.cast<float>());
    }
    frameKey_ = key;
    frameValid_ = true;
    return &frame_;
  } catch (const std::exception&) {
    return nullptr;  // a scene the frame builder cannot show draws nothing rather than crashing
  }
}

std::optional<Vec3> EditorSession::shownPosition(int node) {
  viewportScene();
  if (showingCache_) {
    const auto f = cache_.frame(std::min(playback_.frame(), cache_.frameCount() - 1));
    if (f && node >= 0 && node < f->positions.rows()) return Vec3(f->positions.row(node).transpose());
    return std::nullopt;
  }
  Builder* b = builderFor(lastValidScene_, documentBuilder_);
  if (b && node >= 0 && node < b->model.rest.vertices.rows()) return Vec3(b->model.rest.vertices.row(node).transpose());
  return std::nullopt;
}

std::optional<VertexReport> EditorSession::inspect() const {
  const int node = selection_.focus();
  const int available = cache_.frameCount();
  const std::shared_ptr<const Scene> cached = cache_.scene();
  if (node < 0 || available == 0 || !cached) return std::nullopt;
  if (lastValidScene_ && lastValidScene_->vertexCount() != cached->vertexCount()) return std::nullopt;
  const auto f = cache_.frame(std::min(playback_.frame(), available - 1));
  if (!f) return std::nullopt;
  std::vector<int> offsets{0};
  for (const Cloth& c : cached->cloths) offsets.push_back(offsets.back() + c.mesh.vertexCount());
  return inspectVertex(*f, node, cached->time.dt, offsets);
}

std::string EditorSession::editTargets(const std::string& label, std::vector<FinalTarget> list,
                                       const std::string& coalesceKey) {
  const std::string file = finalTargetFileName(document_.file());
  return document_.editWithSidecar(
      label, [&](nlohmann::json& doc, nlohmann::json& sidecar) { setFinalTargets(doc, sidecar, list, file); },
      coalesceKey);
}

std::string EditorSession::setTargetsFromSelection() {
  if (selection_.empty()) return "select the vertices to set targets for first";
  std::vector<FinalTarget> list = targets();
  for (int node : selection_.nodes()) {
    const auto p = shownPosition(node);
    if (!p) return "vertex " + std::to_string(node) + " is not a cloth vertex of the scene shown";
    bool found = false;
    for (FinalTarget& t : list)
      if (t.node == node) t.position = *p, found = true;
    if (!found) list.push_back({node, *p});
  }
  return editTargets("Set " + std::to_string(selection_.nodes().size()) + " targets", std::move(list));
}

std::string EditorSession::setTarget(int node, const Vec3& position, const std::string& coalesceKey) {
  if (!position.allFinite()) return "a target position must be finite";
  const Scene* scene = lastValidScene_.get();
  if (!scene || node < 0 || node >= scene->vertexCount())
    return "vertex " + std::to_string(node) + " is not a cloth vertex";
  std::vector<FinalTarget> list = targets();
  bool found = false;
  for (FinalTarget& t : list)
    if (t.node == node) t.position = position, found = true;
  if (!found) list.push_back({node, position});
  return editTargets("Set target of vertex " + std::to_string(node), std::move(list), coalesceKey);
}

std::string EditorSession::moveTargets(const std::vector<int>& nodes, const Vec3& delta, const std::string& coalesceKey) {
  if (!delta.allFinite()) return "the offset must be finite";
  std::vector<FinalTarget> list = targets();
  int moved = 0;
  for (FinalTarget& t : list)
    if (std::find(nodes.begin(), nodes.end(), t.node) != nodes.end()) t.position += delta, ++moved;
  if (moved == 0) return "none of the selected vertices has a target";
  return editTargets("Move " + std::to_string(moved) + " targets", std::move(list), coalesceKey);
}

std::string EditorSession::dragTargets(const std::vector<int>& nodes, float dx, float dy, int width, int height,
                                       const std::string& coalesceKey) {
  std::vector<FinalTarget> list = targets();
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

std::string EditorSession::removeTargets(const std::vector<int>& nodes) {
  std::vector<FinalTarget> list = targets(), kept;
  for (const FinalTarget& t : list)
    if (!nodes.empty() && std::find(nodes.begin(), nodes.end(), t.node) == nodes.end()) kept.push_back(t);
  if (kept.size() == list.size()) return list.empty() ? "there are no targets" : "none of these vertices has a target";
  return editTargets("Remove " + std::to_string(list.size() - kept.size()) + " targets", std::move(kept));
}

std::string EditorSession::loadTargetMotion(const std::string& file) {
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
  return document_.edit("Load target motion " + std::filesystem::path(file).filename().string(),
                        [&](nlohmann::json& doc) {
                          if (!doc.contains("task") || !doc["task"].is_object()) doc["task"] = nlohmann::json::object();
                          if (!doc["task"].contains("loss") || !doc["task"]["loss"].is_object())
                            doc["task"]["loss"] = nlohmann::json::object();
                          doc["task"]["loss"]["trajectory"] = {{"target", path}};
                        });
}

std::string EditorSession::removeTargetMotion() {
  if (!document_.find("task.loss.trajectory")) return "the task has no target motion";
  return document_.edit("Remove target motion", [](nlohmann::json& doc) {
    nlohmann::json& task = doc["task"];
    task["loss"].erase("trajectory");
    if (task["loss"].empty() && (!task.contains("parameters") || task["parameters"].empty())) doc.erase("task");
  });
}

const LossValue& EditorSession::liveLoss() { return liveLoss_.evaluate(document_, cache_); }

std::string EditorSession::startOptimizer(const OptimizerRun::Setup& setup, bool paused) {
  if (!document_.valid()) return "the scene does not validate: " + document_.validationError();
  nlohmann::json doc = document_.document();
  const std::vector<FinalTarget> list = targets();
  std::string temporary;
  if (!list.empty()) {
    // The run reads its targets through the engine's TaskLoss, from a file: targets not saved
    // yet go to a private temporary one, read once when the run starts and removed then.
    std::string name = (std::filesystem::temp_directory_path() / "weft-editor-target-XXXXXX").string();
    const int fd = ::mkstemp(name.data());
    if (fd < 0) return "cannot create a temporary target file";
    ::close(fd);
    temporary = name;
    try {
      writeTargetNpy(temporary, finalTargetMatrix(list, buildClothModel(*document_.scene()).rest.vertices));
    } catch (const std::exception& e) {
      ::unlink(temporary.c_str());
      return e.what();
    }
    doc["task"]["loss"]["final"]["target"] = temporary;
  }
  std::string error;
  try {
    const Scene scene = parseScene(doc, document_.file().empty() ? document_.displayName() : document_.file(),
                                   document_.directory());
    error = optimizer_.start(scene, setup, paused);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!temporary.empty()) ::unlink(temporary.c_str());
  return error;
}

std::string EditorSession::setParameterValues(const std::string& label, const std::vector<double>& values) {
  const std::vector<std::string>& paths = optimizer_.parameters();
  if (paths.empty() || values.size() != paths.size()) return "there is no optimisation result to use";
  for (const std::string& path : paths) {
    const nlohmann::json* v = document_.find(path);
    if (!v || !v->is_number()) return path + " is no longer a number in the scene: cannot write the result";
  }
  return document_.edit(label, [&](nlohmann::json& doc) {
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const std::string error = setJsonPath(doc, paths[i], values[i]);
      if (!error.empty()) throw std::runtime_error(paths[i] + ": " + error);
    }
  });
}

std::string EditorSession::applyOptimizerResult() {
  const auto best = optimizer_.best();
  if (!best) return "the optimiser has no evaluation yet";
  return setParameterValues("Apply optimised parameters (loss " + [&] {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", best->loss);
    return std::string(text);
  }() + ")", best->values);
}

std::string EditorSession::revertToOptimizerStart() {
  return setParameterValues("Revert to the optimiser's start values", optimizer_.initialValues());
}

}  // namespace weft::editor
