#pragma once
// What the viewport shows: the cached state at the playback frame (with contact branches and
// force arrows) while the cache fits the mesh being edited, else the document's rest state;
// with the targets the editor holds. The picture is built by the renderer adapter
// (FrameBuilder) and kept until what it shows changes. Also the last scene that validated,
// which the viewport keeps showing while the document does not.

#include "EditorDocument.h"
#include "SimulationCache.h"

#include <weft/model/ClothModel.h>
#include <weft/render/Camera.h>
#include <weft/render/RenderScene.h>

#include <memory>
#include <optional>

namespace weft {
class FrameBuilder;
}

namespace weft::editor {

class ViewportFrame {
 public:
  ViewportFrame(const EditorDocument& document, const SimulationCache& cache,
                const Playback& playback);
  ~ViewportFrame();

  // The picture (null when nothing can be shown). Takes the document's scene as the last valid
  // one when it validates.
  const render::RenderScene* scene();
  // True when the viewport shows a cached state (rather than the rest state).
  bool showingCache() const { return showingCache_; }
  // Changes whenever scene() builds a new picture: the viewport redraws only then (or when the
  // camera or style changes), which leaves the CPU to the simulation and the UI.
  long version() const { return version_; }
  // Where node `node` is shown now, in double precision (unlike the picture); nullopt for a
  // node not shown.
  std::optional<Vec3> shownPosition(int node);
  // The last scene that validated (the document's when it does), as of the last scene() call.
  const std::shared_ptr<const Scene>& lastValidScene() const { return lastValidScene_; }
  // The scene the picture comes from: the cached run's or the last valid one.
  std::shared_ptr<const Scene> shownScene() const;
  // A camera framing the picture, for an image of the given aspect.
  render::Camera framing(float aspect, render::NamedView view);
  // A new document: forget the pictures of the old one.
  void reset();

  // What the viewport overlays on cached states.
  bool contactColours = true;  // vertices coloured by Signorini-Coulomb branch
  bool forceArrows = false;    // contact forces as arrows

 private:
  struct Builder {
    std::shared_ptr<const Scene> scene;
    ClothModel model;
    std::unique_ptr<FrameBuilder> frames;
  };
  Builder* builderFor(const std::shared_ptr<const Scene>& scene, std::unique_ptr<Builder>& slot);

  const EditorDocument& document_;
  const SimulationCache& cache_;
  const Playback& playback_;
  std::unique_ptr<Builder> documentBuilder_, cacheBuilder_;
  std::shared_ptr<const Scene> lastValidScene_;
  render::RenderScene frame_;
  bool showingCache_ = false;
  // What frame_ was built from: rebuilt only when one of these changes (the UI asks for it
  // several times per frame, and a 10k-vertex frame is worth keeping).
  struct FrameKey {
    const void* scene = nullptr;
    long revision = -1, runId = -1;
    int frame = -1;
    bool colours = false, arrows = false;
    bool operator==(const FrameKey& o) const {
      return scene == o.scene && revision == o.revision && runId == o.runId && frame == o.frame &&
             colours == o.colours && arrows == o.arrows;
    }
  } frameKey_;
  bool frameValid_ = false;
  long version_ = 0;
};

}  // namespace weft::editor
