#include "ViewportFrame.h"

#include <weft/frames/FrameBuilder.h>

#include "FinalTargets.h"
#include "VertexInspector.h"

#include <weft/contact/ContactObstacle.h>
#include <weft/render/Bounds.h>

#include <algorithm>

namespace weft::editor {

ViewportFrame::ViewportFrame(const EditorDocument& document, const SimulationCache& cache,
                             const Playback& playback)
    : document_(document), cache_(cache), playback_(playback) {
  lastValidScene_ = document_.sharedScene();
}

ViewportFrame::~ViewportFrame() = default;

void ViewportFrame::reset() {
  documentBuilder_.reset();
  cacheBuilder_.reset();
  lastValidScene_ = document_.sharedScene();
}

std::shared_ptr<const Scene> ViewportFrame::shownScene() const {
  return showingCache_ ? cache_.scene() : lastValidScene_;
}

render::Camera ViewportFrame::framing(float aspect, render::NamedView view) {
  const render::RenderScene* scene = this->scene();
  render::Bounds bounds;
  if (scene) bounds = render::sceneBounds(*scene);
  if (bounds.empty())
    bounds.extend(render::Vec3f(-1, -1, -1)), bounds.extend(render::Vec3f(1, 1, 1));
  return render::namedViewCamera(view, bounds, aspect);
}

ViewportFrame::Builder* ViewportFrame::builderFor(const std::shared_ptr<const Scene>& scene,
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

const render::RenderScene* ViewportFrame::scene() {
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
  ++version_;
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
    const std::vector<FinalTarget> list = finalTargets(document_.sidecar());
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

std::optional<Vec3> ViewportFrame::shownPosition(int node) {
  scene();
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

}  // namespace weft::editor
