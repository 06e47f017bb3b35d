#pragma once
// The editor without a window: the parts it is made of, each with one responsibility, wired to
// one another, and the file actions that replace or write the document (which every part
// follows). The ImGui front end (EditorApp) and the automation script (ScriptRunner) both act
// through these parts, so a scripted session exercises the same code as a person clicking.
//
//   document()    the scene being edited, undo (EditorDocument.h)
//   cache()       the simulated states (SimulationCache.h)
//   timeline()    simulating, playback over the states (Timeline.h)
//   viewport()    the picture the viewport shows (ViewportFrame.h)
//   selection()   the selected vertices (Selection.h); selecting() what is done with them
//                 (SelectionActions.h)
//   placement()   the object the gizmo places, handle keys (ObjectPlacement.h)
//   additions()   garments and obstacles added to the scene (SceneAdditions.h)
//   targets()     the task's targets and loss terms, the live loss (TaskTargets.h)
//   gradients()   the loss gradient of the cached run (StateGradients.h)
//   optimisation() the task's parameters and the optimiser (ParameterOptimisation.h)

#include "Autosave.h"
#include "EditorDocument.h"
#include "ObjectPlacement.h"
#include "ParameterOptimisation.h"
#include "SceneAdditions.h"
#include "Selection.h"
#include "SelectionActions.h"
#include "SimulationCache.h"
#include "StateGradients.h"
#include "StepStatsSeries.h"
#include "TaskTargets.h"
#include "Timeline.h"
#include "VertexInspector.h"
#include "ViewportFrame.h"

#include <weft/render/Camera.h>

#include <optional>
#include <string>

namespace weft::editor {

class EditorSession {
 public:
  // `recentStore`: where the recent-files list lives ("" keeps it in memory only).
  explicit EditorSession(const std::string& recentStore = RecentFiles::defaultStoreFile());
  EditorSession(const EditorSession&) = delete;
  EditorSession& operator=(const EditorSession&) = delete;

  EditorDocument& document() { return document_; }
  const EditorDocument& document() const { return document_; }
  SimulationCache& cache() { return cache_; }
  const SimulationCache& cache() const { return cache_; }
  Timeline& timeline() { return timeline_; }
  const Timeline& timeline() const { return timeline_; }
  Playback& playback() { return playback_; }
  const Playback& playback() const { return playback_; }
  ViewportFrame& viewport() { return viewport_; }
  const ViewportFrame& viewport() const { return viewport_; }
  Selection& selection() { return selection_; }
  const Selection& selection() const { return selection_; }
  SelectionActions& selecting() { return selecting_; }
  ObjectPlacement& placement() { return placement_; }
  const ObjectPlacement& placement() const { return placement_; }
  SceneAdditions& additions() { return additions_; }
  const SceneAdditions& additions() const { return additions_; }
  TaskTargets& targets() { return targets_; }
  const TaskTargets& targets() const { return targets_; }
  StateGradients& gradients() { return gradients_; }
  const StateGradients& gradients() const { return gradients_; }
  ParameterOptimisation& optimisation() { return optimisation_; }
  const ParameterOptimisation& optimisation() const { return optimisation_; }
  render::Camera& camera() { return camera_; }
  const render::Camera& camera() const { return camera_; }
  RecentFiles& recent() { return recent_; }

  // File actions. Errors are InputError (open, save); the document is then unchanged. Saving
  // first writes the editor's final-target .npy next to the scene (when targets were set), then
  // the scene; it returns a warning text ("" normally), e.g. when the targets could not be
  // written because the scene does not validate. Save As into another folder rewrites relative
  // file references to name the same files from there (EditorDocument::saveAs); the targets file
  // the editor owns is written next to the new scene, and a current simulation stays current.
  // The simulation cache goes with the scene: saving writes a finished, current run to the
  // run folder beside it (runFolderBeside: `weft simulate`'s format, SimulationCache::save), and
  // opening reads that folder back when it is the run of the scene as opened
  // (SimulationCache::restore); savedRunNote() says what happened to it.
  void newDocument(nlohmann::json document = EditorDocument::defaultSceneDocument());
  void open(const std::string& file);
  std::string save();
  std::string saveAs(const std::string& file);
  const std::string& savedRunNote() const { return savedRunNote_; }
  // shirt.json -> shirt.run (the extension replaced; added when there is none).
  static std::string runFolderBeside(const std::string& sceneFile);

  // Frames the camera on what the viewport shows, for an image of the given aspect.
  void frameCamera(float aspect, render::NamedView view = render::NamedView::Auto);

  // Contact debugging: the focused vertex (Selection::focus) at the playback frame of the cache,
  // nullopt without a focus or a cached frame fitting the mesh.
  std::optional<VertexReport> inspect() const;
  const StepStatsSeries& stepSeries() const { return stepSeries_; }

  // True while what the window shows changes without any input: playback, or a simulation, an
  // optimisation or a gradient running on a worker (their results are drawn as they come), or
  // an edit waiting for its autosave (at most Autosave's interval). The window waits for input
  // otherwise (main.cpp).
  bool animating() const;

  // Per-frame bookkeeping: playback advance, clamping the frame to the cache, the solver
  // series, an active object gone, a finished gradient job, the autosave.
  void tick(double seconds);

  // Unsaved work kept on disk (Autosave.h); off until set (main.cpp sets it for windows).
  Autosave& autosave() { return autosave_; }
  void setAutosave(Autosave autosave) { autosave_ = std::move(autosave); }
  // Opens the recovery's scene file (a new document for an untitled one) and puts the recovered
  // document over it as one undo step, unsaved; the recovery file goes. Returns an error text.
  std::string restore(const Recovery& recovery);

 private:
  void afterDocumentReplaced();
  std::string saveRunBeside();  // a warning text, "" when saved or nothing to save
  void restoreRunBeside();      // sets savedRunNote_

  // Declared in the order the parts need one another (each refers to those above it).
  EditorDocument document_;
  SimulationCache cache_;
  Playback playback_;
  Selection selection_;
  render::Camera camera_;
  RecentFiles recent_;
  Autosave autosave_;
  StepStatsSeries stepSeries_;
  ViewportFrame viewport_{document_, cache_, playback_};
  Timeline timeline_{document_, cache_, playback_, viewport_};
  ObjectPlacement placement_{document_, timeline_, camera_, viewport_, cache_};
  SelectionActions selecting_{document_, selection_, viewport_, camera_, placement_};
  SceneAdditions additions_{document_};
  TaskTargets targets_{document_, cache_, selection_, viewport_, camera_};
  StateGradients gradients_{document_, cache_, targets_};
  ParameterOptimisation optimisation_{document_, targets_};
  std::string savedRunNote_;
};

}  // namespace weft::editor
