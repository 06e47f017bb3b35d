#pragma once
// Everything the editor knows and does, without a window: the document, the simulation cache
// and its playback, the vertex selection, the orbit camera, and the frame the viewport shows.
// The ImGui front end (EditorApp) and the automation script (ScriptRunner) both act through
// these methods, so a scripted session exercises the same code as a person clicking.

#include "EditorDocument.h"
#include "FinalTargets.h"
#include "Gizmo.h"
#include "LiveLoss.h"
#include "MeshImport.h"
#include "OptimizerRun.h"
#include "Placement.h"
#include "Selection.h"
#include "SimulationCache.h"
#include "StepStatsSeries.h"
#include "VertexInspector.h"

#include <weft/contact/ContactObstacle.h>
#include <weft/model/ClothModel.h>
#include <weft/render/Camera.h>
#include <weft/render/RenderScene.h>

#include <functional>
#include <future>
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

  // File actions. Errors are InputError (open, save); the document is then unchanged. Saving
  // first writes the editor's final-target .npy next to the scene (when targets were set), then
  // the scene; it returns a warning text ("" normally), e.g. when the targets could not be
  // written because the scene does not validate. Save As into another folder rewrites relative
  // file references to name the same files from there (EditorDocument::saveAs); the targets file
  // the editor owns is written next to the new scene, and a current simulation stays current.
  void newDocument(nlohmann::json document = EditorDocument::defaultSceneDocument());
  void open(const std::string& file);
  std::string save();
  std::string saveAs(const std::string& file);

  // Scene building. Each returns an error text ("" on success) and is one undo step; nothing is
  // added when the mesh or shape is rejected.
  MeshImport previewGarment(
      const MeshImportOptions& options) const;  // what importGarment would add
  std::string importGarment(const MeshImportOptions& options);
  std::string addObstacle(const std::string& shape);  // plane, sphere, capsule, box, cylinder
  std::string importMeshObstacle(const MeshImportOptions& options);

  // Starts simulating the current document (`steps`, or the scene's time.steps when < 0).
  // Returns an error text when the document does not validate.
  std::string simulate(int steps = -1);
  bool cacheStale() const { return cache_.staleFor(document_.document()); }
  int availableFrames() const;  // frames the cache holds
  // States the timeline spans: the scene's time.steps + 1, or more when the cache holds more. A
  // state not simulated yet can be shown (the viewport keeps the last cached state) so that keys
  // can be set anywhere on the timeline before simulating.
  int timelineFrames() const;
  // The time of the playback frame: frame * dt of the scene being edited, in seconds.
  double timelineTime() const;

  // Selection in viewport pixels of a width x height view (x right, y down).
  std::optional<int> clickSelect(float x, float y, int width, int height, bool add);
  void boxSelectPixels(float x0, float y0, float x1, float y1, int width, int height, bool add);
  // Ctrl+click: the obstacle or cloth under the pixel (the nearest, as the viewport shows it:
  // ObjectPicking.h) becomes the object the gizmo places; a click that meets nothing takes the
  // gizmo off, as Esc does. Returns an error text ("" also for a click on nothing; activeObject()
  // says what was picked), e.g. when the object shown is no longer in the document.
  std::string clickObject(float x, float y, int width, int height);
  // Selects global nodes; returns an error text for a node that is not a cloth vertex.
  std::string selectNodes(const std::vector<int>& nodes, bool add);
  // Selection by region. The border loop (mesh/BoundaryLoops.h) of the cloth's rest mesh that
  // holds the inspected vertex (a skirt's waist or hem, a cuff); or the cloth vertices whose
  // coordinate `axis` (0 x, 1 y, 2 z) lies in [low, high] as the viewport shows them (a band:
  // the top 2 cm, one side). Error text or "" (also when the band holds no vertex: the
  // selection is then empty, or unchanged when adding).
  std::string selectBoundaryLoop(bool add);
  std::string selectBand(int axis, double low, double high, bool add);
  // Adds a fixed attachment holding the selected vertices (one undo step). Error text or "".
  std::string pinSelection();

  // Adds a handle attachment holding the selected vertices (of one cloth), still until keyed,
  // and makes it the object the gizmo places (one undo step). Error text or "".
  std::string makeHandle();

  // The transform gizmo (Gizmo.h). The active object is what it places: an obstacle, a cloth or
  // a handle ("obstacles.N", "cloths.N", "cloths.N.attachments.M"; "" for none). Obstacles and
  // cloths move in the document, each drag one undo step; a handle's drag moves its offset at
  // the playback frame, which setKey() then records.
  const EditorObject& activeObject() const { return active_; }
  std::string setActiveObject(const std::string& path);
  // The gizmo of the active object in a width x height view; nullopt when there is none or the
  // scene does not validate (its placement is read from the validated scene).
  std::optional<Gizmo> gizmo(int width, int height) const;
  GizmoHandle pickGizmo(float x, float y, int width, int height) const;
  // A drag from pixel (x, y) of the handle, then the mouse's positions, then the release.
  std::string beginGizmoDrag(GizmoHandle handle, float x, float y, int width, int height);
  std::string dragGizmo(float x, float y);
  void endGizmoDrag();
  GizmoHandle draggedHandle() const { return drag_ ? drag_->drag.handle() : GizmoHandle::None; }

  // Keys of the active handle (attachments.M.trajectory.keyframes, or a Hermite spline's knots).
  std::vector<HandleKey> keys() const;
  // The active handle's offset at the playback frame: the one dragged or typed there (pending,
  // until setKey records it), else the trajectory's. nullopt without an active handle or a
  // valid scene.
  std::optional<Vec3> handleOffset() const;
  bool handleOffsetPending() const;
  std::string setHandleOffset(const Vec3& offset);  // typed: pending, like a drag
  // Records the handle's offset as a key at the playback frame's time (replacing a key within
  // half a step of it), or deletes that key; one undo step each, and the cache goes stale.
  std::string setKey();
  std::string deleteKey();
  // Moves the playback frame to the next (+1) or previous (-1) key of the active handle.
  std::string jumpToKey(int direction);

  // Frames the camera on what the viewport shows, for an image of the given aspect.
  void frameCamera(float aspect, render::NamedView view = render::NamedView::Auto);

  // Contact debugging: the focused vertex (Selection::focus) at the playback frame of the cache,
  // nullopt without a focus or a cached frame fitting the mesh.
  std::optional<VertexReport> inspect() const;
  const StepStatsSeries& stepSeries() const { return stepSeries_; }
  // What the viewport overlays on cached states.
  bool contactColours = true;  // vertices coloured by Signorini-Coulomb branch
  bool forceArrows = false;    // contact forces as arrows

  // Final-frame targets (FinalTargets.h). Positions are in metres; "shown" positions are the
  // ones the viewport draws now (the cached frame, or the rest state).
  std::vector<FinalTarget> targets() const { return finalTargets(document_.sidecar()); }
  std::string setTargetsFromSelection();  // a target at each selected vertex's shown position
  std::string setTarget(int node, const Vec3& position, const std::string& coalesceKey = "");
  std::string moveTargets(const std::vector<int>& nodes, const Vec3& delta,
                          const std::string& coalesceKey = "");
  // Moves the targets of `nodes` in the camera's image plane by a pixel offset (x right, y down)
  // of a width x height view, each at its own depth: what dragging them in the viewport does.
  std::string dragTargets(const std::vector<int>& nodes, float dx, float dy, int width, int height,
                          const std::string& coalesceKey = "");
  std::string removeTargets(const std::vector<int>& nodes);  // empty: all
  // A recorded motion (a positions.npy of `weft simulate`, [states >= steps + 1, vertices, 3])
  // as the task's trajectory term; checked by the engine's TaskLoss before it is added.
  std::string loadTargetMotion(const std::string& file);
  std::string removeTargetMotion();
  // The final shape from a mesh file: a final-frame target for every vertex of the cloth whose
  // mesh has as many vertices (the first such cloth), at the file's vertex positions placed as
  // that cloth's own mesh is (its `scale` and `transform`): a target shape exported in the same
  // frame and units as the garment's file. One undo step; error text or "".
  std::string loadTargetMesh(const std::string& file);
  // The built-in hemline term (task.loss.hemline, DiffCloth Eq. 34): the selected vertices'
  // mean squared height gap to `height` (m) at the last state. One undo step each.
  std::string setHemline(double height);
  std::string removeHemline();
  // The task loss of the cached run (LiveLoss.h).
  const LossValue& liveLoss();
  // The loss gradient of the cached run under the task as it is now: dL/dx_n of every state (the
  // backward pass of diff/Backpropagation.h over the cached states and contacts), for the
  // vertex inspector. Starts it on a worker thread (a backward pass costs about as much as the
  // run) and returns at once: error text, or "" when it started. tick() collects the result.
  std::string computeStateGradients();
  bool computingStateGradients() const { return gradientJob_.valid(); }
  // Why the last computation failed ("" when it did not).
  const std::string& stateGradientError() const { return gradientError_; }
  // dL/dx of `node` at `state`, once computed for this cache and task (nullopt otherwise).
  std::optional<Vec3> stateGradient(int node, int state) const;

  // The task's parameters (task.parameters): what the optimiser may change. `path` must be one
  // of differentiableParameterPaths (diff/SceneParameter.h) and the task must have a loss (a
  // task without one does not validate); removing drops the path's bounds too. One undo step
  // each; "" on success, else why not.
  std::string addTaskParameter(const std::string& path);
  std::string removeTaskParameter(const std::string& path);

  // The optimiser (OptimizerRun.h) on a copy of the current document. Targets the editor holds
  // but has not saved yet are written to a private temporary file for the run.
  OptimizerRun& optimizer() { return optimizer_; }
  const OptimizerRun& optimizer() const { return optimizer_; }
  std::string startOptimizer(const OptimizerRun::Setup& setup, bool paused);
  // Writes the best values of the run into the document (one undo step), or its start values.
  std::string applyOptimizerResult();
  std::string revertToOptimizerStart();

  // What the viewport draws now: the cached state at the playback frame (with contact
  // branches) when the cache fits the document's mesh, else the document's rest state. Also
  // the scene the picture comes from (null when nothing can be shown).
  const render::RenderScene* viewportScene();
  // True when the viewport shows a cached state (rather than the rest state).
  bool showingCache() const { return showingCache_; }
  // Changes whenever viewportScene() builds a new picture: the viewport redraws only then (or
  // when the camera or style changes), which leaves the CPU to the simulation and the UI.
  long frameVersion() const { return frameVersion_; }
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
  std::string writeTargets(const std::string& sceneFile);
  std::string editTargets(const std::string& label, std::vector<FinalTarget> targets,
                          const std::string& coalesceKey = "");
  std::optional<Vec3> shownPosition(int node);  // double precision, unlike the render frame
  std::string setParameterValues(const std::string& label, const std::vector<double>& values);
  // Calls `use` with the document's scene whose final term reads the targets the editor holds
  // (from a private temporary file, removed afterwards): what the engine's TaskLoss needs.
  std::string withHeldTargets(const std::function<std::string(const Scene&)>& use);
  // Sets or removes one term of task.loss (one undo step); removing the last term removes the
  // task unless it names parameters. `what` names the term in the error when it is absent.
  std::string setLossTerm(const std::string& term, const nlohmann::json& value,
                          const std::string& label);
  std::string removeLossTerm(const std::string& term, const std::string& label,
                             const std::string& what);
  // The gradient job: its result (dL/dx_n per state) stamped with the cache run and document
  // revision it was computed for, so that any later edit or run makes it stale.
  void collectStateGradients();
  std::future<std::vector<NodeMatrix>> gradientJob_;
  long jobRun_ = -1, jobRevision_ = -1;
  std::vector<NodeMatrix> stateGradients_;
  long gradientsRun_ = -1;
  long gradientsRevision_ = -1;
  std::string gradientError_;
  // The active object's centre in the scene's own (rest) coordinates, from the validated scene;
  // nullopt when it cannot be found. A handle's is where its keys put it at the shown time.
  std::optional<Vec3> objectOrigin() const;
  // Where a moving obstacle is shown at the timeline's time (its motion's pose; identity for
  // everything else): the gizmo sits at shownPose().apply(objectOrigin()).
  RigidPose shownPose() const;
  std::string handleError() const;  // why keys cannot be edited now ("" when they can)
  void dropStaleActiveObject();

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
  long frameVersion_ = 0;
  StepStatsSeries stepSeries_;
  EditorObject active_;
  struct DragState {
    GizmoDrag drag;
    EditorObject object;
    nlohmann::json start;  // the object's entry when the drag began
    Vec3 centre = Vec3::Zero();
    Vec3 startOffset = Vec3::Zero();  // a handle's offset when the drag began
    std::string label, coalesceKey;
  };
  std::optional<DragState> drag_;
  int dragCount_ = 0;  // numbers gizmo drags, so each drag is one undo step
  // A handle offset dragged or typed but not keyed yet: it belongs to one handle at one frame.
  struct PendingOffset {
    EditorObject object;
    int frame = -1;
    Vec3 offset = Vec3::Zero();
  };
  std::optional<PendingOffset> pending_;
  LiveLoss liveLoss_;
  OptimizerRun optimizer_;
};

}  // namespace weft::editor
