#pragma once
// The editor's Dear ImGui front end over an EditorSession: menus, scene panels, the viewport
// (the Renderer drawing into an off-screen target shown as an image, with orbit camera,
// click and box selection), and the timeline. It owns the ImGui context and the OpenGL3
// backend; the platform side (GLFW input, or the headless script feeding ImGui's IO) is the
// caller's: call the platform's NewFrame, then frame().

#include "EditorSession.h"

#include <weft/render/Image.h>
#include <weft/render/RenderContext.h>
#include <weft/render/RenderStyle.h>

#include <memory>
#include <string>

struct ImDrawList;

namespace weft::render {
class Renderer;
}

namespace weft::editor {

class ViewportTarget;
class InspectorPanel;
class TargetPanel;
class OptimiserPanel;
class MeshImportDialog;

// The tabs of the left-hand panel.
enum class PanelTab { Scene, Inspect, Targets, Optimise };
// "scene", "inspect", "targets", "optimise"; false for anything else.
bool parsePanelTab(const std::string& text, PanelTab& tab);

class EditorApp {
 public:
  // `context` is current and outlives the app. Creates the ImGui context (no .ini file: the
  // layout is fixed) and the OpenGL3 renderer backend.
  EditorApp(EditorSession& session, render::RenderContext& context);
  ~EditorApp();
  EditorApp(const EditorApp&) = delete;
  EditorApp& operator=(const EditorApp&) = delete;

  // One UI frame into the context's framebuffer: builds the UI, draws the viewport, renders
  // ImGui. The platform has set io.DisplaySize, io.DeltaTime and input before.
  void frame();

  // The viewport alone, drawn at width x height with the current camera and style.
  render::Image viewportImage(int width, int height);
  // The whole window as last drawn (menus, panels, viewport).
  render::Image windowImage();

  // Viewport size in pixels as laid out by the last frame.
  int viewportWidth() const { return viewportWidth_; }
  int viewportHeight() const { return viewportHeight_; }
  // Where the viewport's top-left pixel lies in the window, as laid out by the last frame.
  int viewportX() const { return viewportX_; }
  int viewportY() const { return viewportY_; }
  render::RenderStyle& style() { return style_; }

  // Closing, New and Open drop the document: a dirty one asks first (Save / Discard / Cancel;
  // Enter saves, Esc cancels), then the action goes on unless cancelled.
  void requestClose();
  void requestNew();
  void requestOpen(const std::string& file);
  bool closeConfirmed() const { return closeConfirmed_; }
  bool closePromptOpen() const { return pending_ == PendingAction::Close; }
  // What the unsaved-changes prompt asks about: "close", "new", "open", "" when it is not open.
  std::string unsavedPrompt() const;

  // The title of the modal dialog Dear ImGui has open (the close prompt, a file dialog, the
  // import dialog), "" for none; `rect` (when given) gets its x, y, width, height in window
  // pixels as last drawn.
  std::string modalDialog(float* rect = nullptr) const;

  // The last user-facing message (an error from an action, or what an action did).
  const std::string& message() const { return message_; }
  bool messageIsError() const { return messageIsError_; }
  // Shows `text` as that message (panels and the script report through it).
  void report(const std::string& text, bool error);

  // The tab the left panel shows (selected by the menus, the user, or a script).
  void showTab(PanelTab tab) { requestedTab_ = tab, tabRequested_ = true; }
  PanelTab tab() const { return tab_; }

 private:
  void drawMenuBar();
  void drawScenePanel(float top, float height);
  void drawViewport(float left, float top, float width, float height);
  void drawTimeline(float left, float top, float width, float height);
  void drawFileDialog();
  void drawUnsavedPrompt();
  void handleShortcuts();
  void renderViewport();
  void drawGizmo(ImDrawList* draw, float originX, float originY, GizmoHandle hovered);
  void pickObjectAt(float x, float y);  // Ctrl+click in the viewport (viewport pixels)
  void keyControls();
  void drawKeyTicks(int frames);
  void placeButton(const std::string& path);

  void doOpen(const std::string& file);
  void doSave();
  void doSaveAs(const std::string& file);
  void doUndo();
  void doRedo();
  void togglePlayback();  // the Play/Pause button and Space

  // Widgets bound to a JSON path of the document. `fallback` is shown when the key is absent.
  bool numberField(const char* label, const std::string& path, double fallback,
                   const char* format = "%.6g");
  bool integerField(const char* label, const std::string& path, int fallback);
  template <class Value, class Widget>
  bool documentField(const char* label, const std::string& path, Value value, Widget&& widget);
  bool vectorField(const char* label, const std::string& path, const double* fallback);
  void comboField(const char* label, const std::string& path, const char* const* options, int count,
                  const char* fallback);
  void applyEdit(const std::string& error, unsigned itemId = 0);

  void timePanel();
  void clothPanel();
  void effectsPanel();
  void obstaclePanel();
  void selectionPanel();
  void sceneTab();

  EditorSession& session_;
  render::RenderContext& context_;
  std::unique_ptr<ViewportTarget> viewport_;
  std::unique_ptr<render::Renderer> renderer_;
  render::RenderStyle style_;
  std::unique_ptr<InspectorPanel> inspector_;
  std::unique_ptr<TargetPanel> targets_;
  std::unique_ptr<OptimiserPanel> optimiser_;
  std::unique_ptr<MeshImportDialog> importDialog_;
  PanelTab tab_ = PanelTab::Scene, requestedTab_ = PanelTab::Scene;
  bool tabRequested_ = false;
  int viewportWidth_ = 1, viewportHeight_ = 1, viewportX_ = 0, viewportY_ = 0;
  bool boxSelecting_ = false;
  bool draggingTargets_ = false;
  bool draggingGizmo_ = false;
  int dragCount_ = 0;  // numbers target drags, so each drag is one undo step
  float boxStart_[2] = {0, 0};
  float targetDragLast_[2] = {0, 0};  // the mouse when a target drag last moved the targets
  // What the viewport texture shows now; it is drawn again only when this changes.
  struct ViewportState {
    long frameVersion = -1;
    int width = 0, height = 0;
    float camera[11] = {};
    bool wireframe = false, legend = false, groundGrid = false;
    bool operator==(const ViewportState& o) const;
  } drawn_;
  int bandAxis_ = 1;  // the Selection panel's band: axis (y) and range (m)
  double band_[2] = {0.9, 1.1};
  unsigned lastEditId_ = 0;  // ImGui item that made the last document edit (coalescing)

  enum class FileDialog { None, Open, SaveAs };
  FileDialog fileDialog_ = FileDialog::None;
  char pathBuffer_[1024] = {};
  bool closeConfirmed_ = false;
  // The action waiting on the unsaved-changes prompt, and the file it opens. `afterSaveAs_` is
  // the action to go on with once the Save As dialog the prompt's Save opened has saved.
  enum class PendingAction { None, Close, New, Open };
  PendingAction pending_ = PendingAction::None, afterSaveAs_ = PendingAction::None;
  std::string pendingFile_;
  void askIfUnsaved(PendingAction action, const std::string& file);
  void carryOut(PendingAction action, const std::string& file);
  std::string message_;
  bool messageIsError_ = false;
};

}  // namespace weft::editor
