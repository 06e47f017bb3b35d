#include "EditorSession.h"

#include <FrameBuilder.h>

#include <weft/core/Error.h>
#include <weft/render/Bounds.h>

namespace weft::editor {

EditorSession::EditorSession(const std::string& recentStore) : recent_(recentStore) {
  lastValidScene_ = document_.sharedScene();
  frameCamera(16.0f / 9.0f);
}

EditorSession::~EditorSession() = default;

void EditorSession::newDocument() {
  cache_.clear();
  document_ = EditorDocument();
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
  selection_.clear();
  playback_ = Playback();
  documentBuilder_.reset();
  cacheBuilder_.reset();
  lastValidScene_ = document_.sharedScene();
  frameCamera(16.0f / 9.0f);
}

void EditorSession::save() {
  document_.save();
  recent_.add(document_.file());
}

void EditorSession::saveAs(const std::string& file) {
  document_.saveAs(file);
  recent_.add(file);
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
}

const render::RenderScene* EditorSession::viewportScene() {
  if (document_.valid()) lastValidScene_ = document_.sharedScene();
  const std::shared_ptr<const Scene> cached = cache_.scene();
  const int available = cache_.frameCount();
  // Cached states are shown while they fit the mesh being edited (same node count), even when
  // stale: the timeline then says so.
  showingCache_ = cached && available > 0 &&
                  (!lastValidScene_ || lastValidScene_->vertexCount() == cached->vertexCount());
  try {
    if (showingCache_) {
      Builder* b = builderFor(cached, cacheBuilder_);
      const int k = std::min(playback_.frame(), available - 1);
      const auto f = cache_.frame(k);
      frame_ = b->frames->frame(f->positions, f->state);
      if (!f->branches.empty()) {
        render::ContactOverlay overlay;
        overlay.branches.reserve(f->branches.size());
        for (std::uint8_t branch : f->branches)
          overlay.branches.push_back(static_cast<render::ContactBranch>(branch));
        frame_.contacts = std::move(overlay);
      }
      return &frame_;
    }
    Builder* b = builderFor(lastValidScene_, documentBuilder_);
    if (!b) return nullptr;
    frame_ = b->frames->frame(b->model.rest.vertices, 0);
    return &frame_;
  } catch (const std::exception&) {
    return nullptr;  // a scene the frame builder cannot show draws nothing rather than crashing
  }
}

}  // namespace weft::editor
