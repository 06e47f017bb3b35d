#pragma once
// Everything the editor knows and does, without a window: the document, the simulation cache
// and its playback, the vertex selection, the orbit camera, and the frame the viewport shows.
// The ImGui front end (EditorApp) and the automation script (ScriptRunner) both act through
// these methods, so a scripted session exercises the same code as a person clicking.

#include "EditorDocument.h"
#include "Selection.h"
#include "SimulationCache.h"

#include <weft/physics/ClothModel.h>
#include <weft/render/Camera.h>
#include <weft/render/RenderScene.h>

#include <memory>
#include <string>
#include <vector>

namespace weft {
class FrameBuilder;
}

namespace weft::editor {

class EditorSession {
 public:
  // `recentStore`: where the recent-files list lives ("" keeps it in memory only).
  explicit EditorSession(const std::string& recentStore = RecentFiles::defaultStoreFile());
  ~EditorSession();

  EditorDocument& document() { return document_; }
  const EditorDocument& document() const { return document_; }
  SimulationCache& cache() { return cache_; }
  const SimulationCache& cache() const { return cache_; }
  Playback& playback() { return playback_; }
  Selection& selection() { return selection_; }
  const Selection& selection() const { return selection_; }
  render::Camera& camera() { return camera_; }
  RecentFiles& recent() { return recent_; }

  // File actions. Errors are InputError (open, save); the document is then unchanged.
  void newDocument();
  void open(const std::string& file);
  void save();
  void saveAs(const std::string& file);

  // Starts simulating the current document (`steps`, or the scene's time.steps when < 0).
  // Returns an error text when the document does not validate.
  std::string simulate(int steps = -1);
  bool cacheStale() const { return cache_.staleFor(document_.document()); }
  int availableFrames() const;  // frames the timeline can show

  // Selection in viewport pixels of a width x height view (x right, y down).
  std::optional<int> clickSelect(float x, float y, int width, int height, bool add);
  void boxSelectPixels(float x0, float y0, float x1, float y1, int width, int height, bool add);
  // Selects global nodes; returns an error text for a node that is not a cloth vertex.
  std::string selectNodes(const std::vector<int>& nodes, bool add);
  // Adds a fixed attachment holding the selected vertices (one undo step). Error text or "".
  std::string pinSelection();

  // Frames the camera on what the viewport shows, for an image of the given aspect.
  void frameCamera(float aspect, render::NamedView view = render::NamedView::Auto);

  // What the viewport draws now: the cached state at the playback frame (with contact
  // branches) when the cache fits the document's mesh, else the document's rest state. Also
  // the scene the picture comes from (null when nothing can be shown).
  const render::RenderScene* viewportScene();
  // True when the viewport shows a cached state (rather than the rest state).
  bool showingCache() const { return showingCache_; }
  // Per-frame bookkeeping: playback advance, clamping the frame to the cache.
  void tick(double seconds);

 private:
  struct Builder {
    std::shared_ptr<const Scene> scene;
    ClothModel model;
    std::unique_ptr<FrameBuilder> frames;
  };
  Builder* builderFor(const std::shared_ptr<const Scene>& scene, std::unique_ptr<Builder>& slot);
  void afterDocumentReplaced();

  EditorDocument document_;
  SimulationCache cache_;
  Playback playback_;
  Selection selection_;
  render::Camera camera_;
  RecentFiles recent_;
  std::unique_ptr<Builder> documentBuilder_, cacheBuilder_;
  std::shared_ptr<const Scene> lastValidScene_;
  render::RenderScene frame_;
  bool showingCache_ = false;
};

}  // namespace weft::editor
