#include "EditorSession.h"

#include <FrameBuilder.h>

#include "ObjectPicking.h"
#include "ObstacleTemplates.h"

#include <weft/core/Error.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/SceneParameter.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/MeshReader.h>
#include <weft/mesh/BoundaryLoops.h>
#include <weft/render/Bounds.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace weft::editor {
namespace {

// The entry at `path` of a document copy being edited; throws when it is gone (an undo during a
// drag can take it away), which the document turns into the edit's error text.
nlohmann::json& entryAt(nlohmann::json& document, const std::string& path) {
  nlohmann::json* entry = findJsonPath(document, path);
  if (!entry) throw std::runtime_error(path + " is no longer in the scene");
  return *entry;
}

}  // namespace

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
  active_ = EditorObject();
  drag_.reset();
  pending_.reset();
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
                 finalTargetMatrix(list, buildClothModel(*scene).rest.vertices));
  return "";
}

std::string EditorSession::save() {
  if (document_.file().empty())
    throw InputError("untitled", "-", "the document has no file yet: use Save As");
  const std::string warning = writeTargets(document_.file());
  document_.save();
  recent_.add(document_.file());
  return warning;
}

std::string EditorSession::saveAs(const std::string& file) {
  if (file.empty()) throw InputError("-", "-", "no file name given");
  const std::string warning = writeTargets(file);
  const bool current = cache_.scene() && !cacheStale();
  document_.saveAs(file);
  // Rebased references name the same files: the cached run is still the document's own.
  if (current && document_.valid()) cache_.relabel(document_.sharedScene());
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
    if (!doc.contains("cloths") || !doc["cloths"].is_array())
      doc["cloths"] = nlohmann::json::array();
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
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array())
      doc["obstacles"] = nlohmann::json::array();
    doc["obstacles"].push_back(obstacle);
  });
}

std::string EditorSession::importMeshObstacle(const MeshImportOptions& options) {
  const MeshImport prepared = prepareMeshObstacle(options, document_.file(), document_.directory());
  if (!prepared.ok()) return prepared.error;
  const std::string name = std::filesystem::path(options.file).filename().string();
  return document_.edit("Add mesh obstacle " + name, [&](nlohmann::json& doc) {
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array())
      doc["obstacles"] = nlohmann::json::array();
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

int EditorSession::availableFrames() const {
  return cache_.frameCount();
}

int EditorSession::timelineFrames() const {
  const Scene* scene = document_.valid() ? document_.scene() : lastValidScene_.get();
  return std::max(cache_.frameCount(), scene ? scene->time.steps + 1 : 1);
}

double EditorSession::timelineTime() const {
  const Scene* scene = document_.valid() ? document_.scene() : lastValidScene_.get();
  // Rounded to 1e-12 s so that a key written at frame 3 of dt = 0.0111 reads 0.0333 in the file
  // rather than 0.033299999999999996; far below any time step the simulator compares against.
  return scene ? std::round(playback_.frame() * scene->time.dt * 1e12) / 1e12 : 0.0;
}

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

std::string EditorSession::clickObject(float x, float y, int width, int height) {
  const render::RenderScene* frame = viewportScene();
  // The scene the picture comes from, at the time of the state it shows.
  const std::shared_ptr<const Scene> shown = showingCache_ ? cache_.scene() : lastValidScene_;
  if (!frame || !shown) return "there is nothing in the viewport to pick";
  double time = 0.0;
  if (showingCache_)
    if (const auto f = cache_.frame(std::min(playback_.frame(), cache_.frameCount() - 1)))
      time = f->state * shown->time.dt;
  // Planes count where they are drawn (the renderer's square around the rest of the frame).
  const render::Bounds bounds = render::sceneBounds(*frame);
  const DrawnPlaneExtent planes{
      bounds.empty() ? Vec3(camera_.target.cast<double>()) : Vec3(bounds.center().cast<double>()),
      double(render::planeHalfSize(bounds))};
  const auto hit = pickObject(*shown, time, frame->cloth, pixelRay(camera_, x, y, width, height),
                              camera_.farPlane, planes);
  return setActiveObject(hit ? hit->object.path() : "");
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

namespace {

// The cloth a global node belongs to (ClothModel numbers cloths' vertices one after another),
// -1 when it is no cloth vertex.
int clothOfNode(const ClothModel& model, int node) {
  if (node < 0 || node >= model.vertexOffset.back()) return -1;
  return int(std::upper_bound(model.vertexOffset.begin(), model.vertexOffset.end(), node) -
             model.vertexOffset.begin()) -
         1;
}

}  // namespace

std::string EditorSession::selectBoundaryLoop(bool add) {
  const int node = selection_.focus();
  if (node < 0) return "click a vertex on the border first (its loop is selected)";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel model = buildClothModel(*scene);
  const int cloth = clothOfNode(model, node);
  if (cloth < 0) return "vertex " + std::to_string(node) + " is not a cloth vertex";
  const int offset = model.vertexOffset[std::size_t(cloth)];
  for (const std::vector<int>& loop : boundaryLoops(scene->cloths[std::size_t(cloth)].mesh)) {
    if (std::find(loop.begin(), loop.end(), node - offset) == loop.end()) continue;
    std::vector<int> nodes;
    for (int v : loop) nodes.push_back(v + offset);
    if (add)
      selection_.add(nodes);
    else
      selection_.set(nodes);
    return "";
  }
  return "vertex " + std::to_string(node) + " is not on a border of its cloth";
}

std::string EditorSession::selectBand(int axis, double low, double high, bool add) {
  if (axis < 0 || axis > 2) return "the axis is x, y or z";
  if (!(low <= high)) return "the band's low end is above its high end";
  const render::RenderScene* shown = viewportScene();
  if (!shown) return "the scene does not validate: " + document_.validationError();
  std::vector<int> nodes;
  const auto& positions = shown->cloth.positions;
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    if (positions(v, axis) >= low && positions(v, axis) <= high) nodes.push_back(int(v));
  if (add)
    selection_.add(nodes);
  else
    selection_.set(nodes);
  return "";
}

std::string EditorSession::pinSelection() {
  if (selection_.empty()) return "nothing is selected";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel model = buildClothModel(*scene);
  const std::vector<int> nodes = selection_.nodes();
  return document_.edit(
      "Pin " + std::to_string(nodes.size()) + " vertices",
      [&](nlohmann::json& doc) { addFixedAttachments(doc, nodes, model.vertexOffset); });
}

std::string EditorSession::makeHandle() {
  if (selection_.empty()) return "select the vertices the handle holds first";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel model = buildClothModel(*scene);
  const std::vector<int> nodes = selection_.nodes();
  const int cloth = clothOfNode(model, nodes.front());
  if (cloth < 0 || clothOfNode(model, nodes.back()) < 0)
    return "the selection is not cloth vertices";
  if (clothOfNode(model, nodes.back()) != cloth)
    return "a handle holds vertices of one cloth: select vertices of one cloth only";
  std::vector<int> local;
  for (int n : nodes) local.push_back(n - model.vertexOffset[std::size_t(cloth)]);
  const std::string base = "cloths." + std::to_string(cloth);
  const nlohmann::json* attachments = document_.find(base + ".attachments");
  const int index = attachments && attachments->is_array() ? int(attachments->size()) : 0;
  const std::string error = document_.edit(
      "Make a handle of " + std::to_string(nodes.size()) + " vertices", [&](nlohmann::json& doc) {
        nlohmann::json& c = doc.at("cloths").at(std::size_t(cloth));
        if (!c.contains("attachments")) c["attachments"] = nlohmann::json::array();
        c["attachments"].push_back(newHandleAttachment(local));
      });
  if (!error.empty()) return error;
  return setActiveObject(base + ".attachments." + std::to_string(index));
}

std::string EditorSession::setActiveObject(const std::string& path) {
  EditorObject object;
  const std::string error = findEditorObject(document_.document(), path, object);
  if (!error.empty()) return error;
  if (object != active_) endGizmoDrag();
  active_ = object;
  return "";
}

void EditorSession::dropStaleActiveObject() {
  // An undo or a removal can take the active object away (or turn a handle into a fixed pin).
  EditorObject still;
  if (active_.kind != EditorObject::Kind::None &&
      !findEditorObject(document_.document(), active_.path(), still).empty()) {
    active_ = EditorObject();
    drag_.reset();
  }
}

std::optional<Vec3> EditorSession::objectOrigin() const {
  const Scene* scene = document_.scene();
  if (!scene) return std::nullopt;
  auto boundsCentre = [](const NodeMatrix& v) -> std::optional<Vec3> {
    if (v.rows() == 0) return std::nullopt;
    return Vec3(0.5 * (v.colwise().minCoeff() + v.colwise().maxCoeff()).transpose());
  };
  switch (active_.kind) {
    case EditorObject::Kind::None:
      return std::nullopt;
    case EditorObject::Kind::Obstacle: {
      if (active_.index >= int(scene->obstacles.size())) return std::nullopt;
      const Obstacle& o = scene->obstacles[std::size_t(active_.index)];
      switch (o.shape) {
        case Obstacle::Shape::Plane:
          return o.point;
        case Obstacle::Shape::Sphere:
        case Obstacle::Shape::Box:
          return o.center;
        case Obstacle::Shape::Capsule:
        case Obstacle::Shape::Cylinder:
          return Vec3(0.5 * (o.a + o.b));
        case Obstacle::Shape::Mesh:
          return boundsCentre(o.mesh.vertices);
      }
      return std::nullopt;
    }
    case EditorObject::Kind::Cloth:
      if (active_.index >= int(scene->cloths.size())) return std::nullopt;
      return boundsCentre(scene->cloths[std::size_t(active_.index)].mesh.vertices);
    case EditorObject::Kind::Handle: {
      if (active_.index >= int(scene->cloths.size())) return std::nullopt;
      const Cloth& cloth = scene->cloths[std::size_t(active_.index)];
      if (active_.attachment >= int(cloth.attachments.size())) return std::nullopt;
      const Attachment& a = cloth.attachments[std::size_t(active_.attachment)];
      if (a.vertices.empty()) return std::nullopt;
      Vec3 centroid = Vec3::Zero();
      for (int v : a.vertices) centroid += cloth.mesh.vertices.row(v).transpose();
      centroid /= double(a.vertices.size());
      // Where the trajectory puts the centroid now, with the offset being edited in place of its
      // own.
      const double t = timelineTime();
      const auto offset = handleOffset();
      return Vec3(a.trajectory.target(centroid, t) - a.trajectory.offset(t) +
                  offset.value_or(a.trajectory.offset(t)));
    }
  }
  return std::nullopt;
}

RigidPose EditorSession::shownPose() const {
  const Scene* scene = document_.scene();
  if (!scene || active_.kind != EditorObject::Kind::Obstacle ||
      active_.index >= int(scene->obstacles.size()))
    return RigidPose();
  const Obstacle& o = scene->obstacles[std::size_t(active_.index)];
  return o.motion ? poseAt(*o.motion, timelineTime()) : RigidPose();
}

std::optional<Gizmo> EditorSession::gizmo(int width, int height) const {
  const auto origin = objectOrigin();
  if (!origin || !origin->allFinite()) return std::nullopt;
  // A moving obstacle's gizmo sits on the obstacle as the viewport shows it at this time.
  const Vec3 shown = shownPose().apply(*origin);
  return Gizmo(shown.cast<float>(), objectRotates(document_.document(), active_), camera_, width,
               height);
}

GizmoHandle EditorSession::pickGizmo(float x, float y, int width, int height) const {
  const auto g = gizmo(width, height);
  return g ? g->pickPixel(x, y) : GizmoHandle::None;
}

std::string EditorSession::beginGizmoDrag(GizmoHandle handle, float x, float y, int width,
                                          int height) {
  endGizmoDrag();
  const auto g = gizmo(width, height);
  if (!g) {
    if (active_.kind == EditorObject::Kind::None)
      return "nothing to move: choose an obstacle, a cloth or a handle first";
    return "the scene does not validate: " + document_.validationError();
  }
  if (!g->has(handle))
    return std::string("this object has no ") + gizmoHandleName(handle) + " handle";
  if (active_.kind == EditorObject::Kind::Handle && !handleError().empty()) return handleError();
  auto drag = GizmoDrag::begin(*g, handle, Eigen::Vector2f(x, y));
  if (!drag)
    return isRotation(handle) ? "press on the ring, away from the gizmo's centre"
                              : "this axis points at the camera: turn the view to drag along it";
  const char* axes = "XYZ";
  DragState state{*drag, active_, nlohmann::json(), Vec3(g->origin().cast<double>()), Vec3::Zero(),
                  "",    ""};
  if (active_.kind == EditorObject::Kind::Handle) {
    state.startOffset = handleOffset().value_or(Vec3::Zero());
  } else {
    const nlohmann::json* entry = document_.find(active_.path());
    if (!entry) return active_.path() + " is no longer in the scene";
    state.start = *entry;
    // The exact centre from the scene, not the gizmo's single-precision copy.
    state.centre = objectOrigin().value_or(state.centre);
  }
  state.label = std::string(isRotation(handle) ? "Turn " : "Move ") + active_.path() +
                (isRotation(handle) ? " about " : " along ") + axes[gizmoAxis(handle)];
  state.coalesceKey = "gizmo drag " + std::to_string(++dragCount_);
  drag_ = std::move(state);
  return "";
}

std::string EditorSession::dragGizmo(float x, float y) {
  if (!drag_) return "no gizmo drag in progress";
  if (drag_->object != active_) {
    drag_.reset();
    return "the object being moved has gone";
  }
  const double amount = drag_->drag.update(Eigen::Vector2f(x, y));
  const GizmoHandle handle = drag_->drag.handle();
  const int axis = gizmoAxis(handle);
  if (active_.kind == EditorObject::Kind::Handle) {
    Vec3 offset = drag_->startOffset;
    offset[axis] += amount;
    pending_ = PendingOffset{active_, playback_.frame(), offset};
    return "";
  }
  nlohmann::json entry = drag_->start;
  // A moving obstacle is dragged where it is shown; the scene holds its rest pose, which the
  // motion turns by R: a world move d is R^T d at rest. A turn about a world axis is one about a
  // rest axis only while R is the identity.
  const Mat3 shownRotation = shownPose().rotation;
  const bool turned = !shownRotation.isApprox(Mat3::Identity(), 1e-12);
  if (turned && isRotation(handle))
    return active_.path() +
           ": its motion has turned it at this time; turn it at a time where it is not turned "
           "(e.g. frame 0)";
  try {
    if (isRotation(handle)) {
      rotateObject(entry, active_.kind, axis, amount, drag_->centre);
    } else if (!turned) {
      translateObject(entry, active_.kind, axis, amount);
    } else {
      const Vec3 atRest = shownRotation.transpose() * (amount * Vec3::Unit(axis));
      for (int k = 0; k < 3; ++k)
        if (atRest[k] != 0.0) translateObject(entry, active_.kind, k, atRest[k]);
    }
  } catch (const std::exception& e) {
    return active_.path() + ": " + e.what();
  }
  const std::string path = active_.path();
  // One undo step per drag: every move of the same drag merges into the step it started.
  return document_.editWithSidecar(
      drag_->label, [&](nlohmann::json& doc, nlohmann::json&) { entryAt(doc, path) = entry; },
      drag_->coalesceKey);
}

void EditorSession::endGizmoDrag() {
  drag_.reset();
}

std::string EditorSession::handleError() const {
  if (active_.kind != EditorObject::Kind::Handle)
    return "choose a handle first (make one from a selection)";
  if (!document_.valid()) return "the scene does not validate: " + document_.validationError();
  const nlohmann::json* attachment = document_.find(active_.path());
  if (!attachment || !hasKeyframes(*attachment))
    return "this handle follows a Hermite spline: edit its knots and tangents in the scene file";
  return "";
}

std::vector<HandleKey> EditorSession::keys() const {
  if (active_.kind != EditorObject::Kind::Handle) return {};
  const nlohmann::json* attachment = document_.find(active_.path());
  return attachment ? handleKeys(*attachment) : std::vector<HandleKey>{};
}

std::optional<Vec3> EditorSession::handleOffset() const {
  if (active_.kind != EditorObject::Kind::Handle) return std::nullopt;
  if (handleOffsetPending()) return pending_->offset;
  const Scene* scene = document_.scene();
  if (!scene || active_.index >= int(scene->cloths.size())) return std::nullopt;
  const Cloth& cloth = scene->cloths[std::size_t(active_.index)];
  if (active_.attachment >= int(cloth.attachments.size())) return std::nullopt;
  return cloth.attachments[std::size_t(active_.attachment)].trajectory.offset(timelineTime());
}

bool EditorSession::handleOffsetPending() const {
  return pending_ && active_.kind == EditorObject::Kind::Handle && pending_->object == active_ &&
         pending_->frame == playback_.frame();
}

std::string EditorSession::setHandleOffset(const Vec3& offset) {
  const std::string error = handleError();
  if (!error.empty()) return error;
  if (!offset.allFinite()) return "the offset must be finite";
  pending_ = PendingOffset{active_, playback_.frame(), offset};
  return "";
}

std::string EditorSession::setKey() {
  std::string error = handleError();
  if (!error.empty()) return error;
  const auto offset = handleOffset();
  if (!offset) return "the handle has no offset here";
  const double t = timelineTime();
  const double dt = document_.scene()->time.dt;
  const std::string path = active_.path();
  char label[64];
  std::snprintf(label, sizeof label, "Set key at t = %.4g s", t);
  error = document_.edit(
      label, [&](nlohmann::json& doc) { setHandleKey(entryAt(doc, path), t, *offset, 0.5 * dt); });
  if (error.empty()) pending_.reset();
  return error;
}

std::string EditorSession::deleteKey() {
  std::string error = handleError();
  if (!error.empty()) return error;
  const double t = timelineTime();
  const double dt = document_.scene()->time.dt;
  const std::vector<HandleKey> list = keys();
  bool here = false;
  for (const HandleKey& k : list) here = here || std::abs(k.time - t) < 0.5 * dt;
  if (!here) return "there is no key at this frame";
  if (list.size() == 1) return "a handle needs at least one key: remove the attachment instead";
  const std::string path = active_.path();
  char label[64];
  std::snprintf(label, sizeof label, "Delete key at t = %.4g s", t);
  error = document_.edit(
      label, [&](nlohmann::json& doc) { deleteHandleKey(entryAt(doc, path), t, 0.5 * dt); });
  if (error.empty()) pending_.reset();
  return error;
}

std::string EditorSession::jumpToKey(int direction) {
  const Scene* scene = document_.valid() ? document_.scene() : lastValidScene_.get();
  if (active_.kind != EditorObject::Kind::Handle || !scene) return "choose a handle first";
  const int frame = playback_.frame();
  int best = -1;
  for (const HandleKey& k : keys()) {
    const int f = int(std::llround(k.time / scene->time.dt));
    if (direction > 0 ? f > frame && (best < 0 || f < best)
                      : f < frame && f >= 0 && (best < 0 || f > best))
      best = f;
  }
  if (best < 0) return direction > 0 ? "no key after this frame" : "no key before this frame";
  playback_.scrub(best, timelineFrames());
  playback_.pause();
  return "";
}

void EditorSession::frameCamera(float aspect, render::NamedView view) {
  const render::RenderScene* scene = viewportScene();
  render::Bounds bounds;
  if (scene) bounds = render::sceneBounds(*scene);
  if (bounds.empty())
    bounds.extend(render::Vec3f(-1, -1, -1)), bounds.extend(render::Vec3f(1, 1, 1));
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
  const int frames = timelineFrames();
  if (playback_.frame() >= frames) playback_.scrub(playback_.frame(), frames);
  stepSeries_.update(cache_);
  dropStaleActiveObject();
  collectStateGradients();
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
    if (f && node >= 0 && node < f->positions.rows())
      return Vec3(f->positions.row(node).transpose());
    return std::nullopt;
  }
  Builder* b = builderFor(lastValidScene_, documentBuilder_);
  if (b && node >= 0 && node < b->model.rest.vertices.rows())
    return Vec3(b->model.rest.vertices.row(node).transpose());
  return std::nullopt;
}

std::optional<VertexReport> EditorSession::inspect() const {
  const int node = selection_.focus();
  const int available = cache_.frameCount();
  const std::shared_ptr<const Scene> cached = cache_.scene();
  if (node < 0 || available == 0 || !cached) return std::nullopt;
  if (lastValidScene_ && lastValidScene_->vertexCount() != cached->vertexCount())
    return std::nullopt;
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
      label,
      [&](nlohmann::json& doc, nlohmann::json& sidecar) {
        setFinalTargets(doc, sidecar, list, file);
      },
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
  return editTargets("Set " + std::to_string(selection_.nodes().size()) + " targets",
                     std::move(list));
}

std::string EditorSession::setTarget(int node, const Vec3& position,
                                     const std::string& coalesceKey) {
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

std::string EditorSession::moveTargets(const std::vector<int>& nodes, const Vec3& delta,
                                       const std::string& coalesceKey) {
  if (!delta.allFinite()) return "the offset must be finite";
  std::vector<FinalTarget> list = targets();
  int moved = 0;
  for (FinalTarget& t : list)
    if (std::find(nodes.begin(), nodes.end(), t.node) != nodes.end()) t.position += delta, ++moved;
  if (moved == 0) return "none of the selected vertices has a target";
  return editTargets("Move " + std::to_string(moved) + " targets", std::move(list), coalesceKey);
}

std::string EditorSession::dragTargets(const std::vector<int>& nodes, float dx, float dy, int width,
                                       int height, const std::string& coalesceKey) {
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
    if (!nodes.empty() && std::find(nodes.begin(), nodes.end(), t.node) == nodes.end())
      kept.push_back(t);
  if (kept.size() == list.size())
    return list.empty() ? "there are no targets" : "none of these vertices has a target";
  return editTargets("Remove " + std::to_string(list.size() - kept.size()) + " targets",
                     std::move(kept));
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
  return setLossTerm("trajectory", {{"target", path}},
                     "Load target motion " + std::filesystem::path(file).filename().string());
}

std::string EditorSession::loadTargetMesh(const std::string& file) {
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const std::string path = std::filesystem::absolute(file).string();
  const ClothModel model = buildClothModel(*scene);
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
    for (const FinalTarget& t : targets())  // other cloths' targets stay
      if (t.node < offset || t.node >= offset + n) list.push_back(t);
    for (int v = 0; v < n; ++v) list.push_back({offset + v, shape.vertices.row(v).transpose()});
    return editTargets("Target shape " + std::filesystem::path(file).filename().string(),
                       std::move(list));
  }
  return file + ": " + std::to_string(readMesh(path).vertexCount()) + " vertices, but " + counts +
         " (a target shape has the garment's vertices, in its order)";
}

std::string EditorSession::setHemline(double height) {
  if (!std::isfinite(height)) return "the hemline height must be a finite number";
  if (selection_.empty()) return "select the hemline's vertices first (e.g. the hem's border loop)";
  const std::vector<int> nodes = selection_.nodes();
  return setLossTerm("hemline", {{"vertices", nodes}, {"height", height}},
                     "Hemline of " + std::to_string(nodes.size()) + " vertices");
}

std::string EditorSession::removeHemline() {
  return removeLossTerm("hemline", "Remove hemline", "hemline term");
}

std::string EditorSession::removeTargetMotion() {
  return removeLossTerm("trajectory", "Remove target motion", "target motion");
}

std::string EditorSession::setLossTerm(const std::string& term, const nlohmann::json& value,
                                       const std::string& label) {
  return document_.edit(label, [&](nlohmann::json& doc) {
    if (!doc.contains("task") || !doc["task"].is_object()) doc["task"] = nlohmann::json::object();
    if (!doc["task"].contains("loss") || !doc["task"]["loss"].is_object())
      doc["task"]["loss"] = nlohmann::json::object();
    doc["task"]["loss"][term] = value;
  });
}

std::string EditorSession::removeLossTerm(const std::string& term, const std::string& label,
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

const LossValue& EditorSession::liveLoss() {
  return liveLoss_.evaluate(document_, cache_);
}

std::string EditorSession::withHeldTargets(const std::function<std::string(const Scene&)>& use) {
  if (!document_.valid()) return "the scene does not validate: " + document_.validationError();
  nlohmann::json doc = document_.document();
  const std::vector<FinalTarget> list = targets();
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
      writeTargetNpy(temporary,
                     finalTargetMatrix(list, buildClothModel(*document_.scene()).rest.vertices));
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

std::string EditorSession::startOptimizer(const OptimizerRun::Setup& setup, bool paused) {
  return withHeldTargets(
      [&](const Scene& scene) { return optimizer_.start(scene, setup, paused); });
}

std::string EditorSession::computeStateGradients() {
  if (gradientJob_.valid()) return "the loss gradient is being computed";
  const Scene* current = document_.scene();
  if (!current) return "the scene does not validate: " + document_.validationError();
  if (!current->task) return "the scene has no task: set targets or load a target motion first";
  const int frames = cache_.frameCount();
  if (cache_.status() != SimulationCache::Status::Done || frames != current->time.steps + 1 ||
      cache_.staleFor(document_.document()))
    return "simulate the scene (all time.steps) first: the gradient is of the cached run";
  auto trajectory = std::make_shared<const Trajectory>(cache_.trajectory());
  // The loss is built here, while the editor's targets are in their temporary file; the job
  // owns copies of everything it reads.
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const TaskLoss> loss;
  const std::string error = withHeldTargets([&](const Scene& s) {
    scene = std::make_shared<const Scene>(s);
    loss = std::make_shared<const TaskLoss>(*scene);
    return std::string();
  });
  if (!error.empty()) return error;
  gradientError_.clear();
  jobRun_ = cache_.runId();
  jobRevision_ = document_.revision();
  gradientJob_ = std::async(std::launch::async, [scene, loss, trajectory] {
    // Per-vertex values show a solve's error more than a parameter's sum does: solve tightly.
    BackwardSettings settings = scene->solver.backward;
    settings.tolerance = std::min(settings.tolerance, 1e-8);
    return backpropagate(*scene, *trajectory, *loss, ParameterSet(), settings).dLdx;
  });
  return "";
}

void EditorSession::collectStateGradients() {
  if (!gradientJob_.valid() ||
      gradientJob_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  try {
    stateGradients_ = gradientJob_.get();
    gradientsRun_ = jobRun_;
    gradientsRevision_ = jobRevision_;
  } catch (const std::exception& e) {
    gradientError_ = std::string("the backward pass failed: ") + e.what();
  }
}

std::optional<Vec3> EditorSession::stateGradient(int node, int state) const {
  if (gradientsRun_ != cache_.runId() || gradientsRevision_ != document_.revision())
    return std::nullopt;
  if (state < 0 || state >= int(stateGradients_.size()) || node < 0 ||
      node >= stateGradients_[std::size_t(state)].rows())
    return std::nullopt;
  return Vec3(stateGradients_[std::size_t(state)].row(node).transpose());
}

std::string EditorSession::setParameterValues(const std::string& label,
                                              const std::vector<double>& values) {
  const std::vector<std::string>& paths = optimizer_.parameters();
  if (paths.empty() || values.size() != paths.size())
    return "there is no optimisation result to use";
  for (const std::string& path : paths) {
    const nlohmann::json* v = document_.find(path);
    if (!v || !v->is_number())
      return path + " is no longer a number in the scene: cannot write the result";
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
  return setParameterValues(
      "Apply optimised parameters (loss " +
          [&] {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", best->loss);
            return std::string(text);
          }() +
          ")",
      best->values);
}

std::string EditorSession::revertToOptimizerStart() {
  return setParameterValues("Revert to the optimiser's start values", optimizer_.initialValues());
}

std::string EditorSession::addTaskParameter(const std::string& path) {
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  if (!scene->task)
    return "the task has no loss yet: set targets or load a target motion first (Targets tab)";
  const std::vector<std::string>& chosen = scene->task->parameters;
  if (std::find(chosen.begin(), chosen.end(), path) != chosen.end())
    return path + " is already a parameter";
  const std::vector<std::string> offered = differentiableParameterPaths(*scene);
  if (std::find(offered.begin(), offered.end(), path) == offered.end()) {
    try {  // the engine's own reason (no such value, not differentiable)
      resolveSceneParameter(*scene, path, "task.parameters");
    } catch (const InputError& e) {
      return e.reason();
    }
    return path + " is not a parameter of this scene";
  }
  return document_.edit("Add parameter " + path, [&](nlohmann::json& doc) {
    nlohmann::json& list = doc["task"]["parameters"];
    if (!list.is_array()) list = nlohmann::json::array();
    list.push_back(path);
  });
}

std::string EditorSession::removeTaskParameter(const std::string& path) {
  const nlohmann::json* list = document_.find("task.parameters");
  if (!list || !list->is_array() || std::find(list->begin(), list->end(), path) == list->end())
    return path + " is not a parameter of the task";
  return document_.edit("Remove parameter " + path, [&](nlohmann::json& doc) {
    nlohmann::json& task = doc["task"];
    nlohmann::json kept = nlohmann::json::array();
    for (const nlohmann::json& p : task["parameters"])
      if (p != path) kept.push_back(p);
    if (kept.empty())
      task.erase("parameters");
    else
      task["parameters"] = kept;
    if (task.contains("bounds") && task["bounds"].is_object()) {
      task["bounds"].erase(path);
      if (task["bounds"].empty()) task.erase("bounds");
    }
  });
}

}  // namespace weft::editor
