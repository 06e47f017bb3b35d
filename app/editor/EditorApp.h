#pragma once
// The editor's Dear ImGui front end over an EditorSession: the frame loop and the window's
// layout (menus, the left panel's tabs, the viewport, the timeline), shortcuts, and the file
// dialogs with the unsaved-changes prompt. Each panel is drawn by its own class (ScenePanel,
// InspectorPanel, TargetPanel, OptimiserPanel, ViewportPanel, TimelinePanel, MeshImportDialog).
// It owns the ImGui context and the OpenGL3 backend; the platform side (GLFW input, or the headless
// script feeding ImGui's IO) is the caller's: call the platform's NewFrame, then frame().

#include "EditorSession.h"
#include "FileBrowser.h"
#include "MeshImportDialog.h"

#include <weft/render/Image.h>
#include <weft/render/RenderContext.h>
#include <weft/render/RenderStyle.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace weft::editor {

class ViewportPanel;
class ScenePanel;
class TimelinePanel;
class InspectorPanel;
class TargetPanel;
class OptimiserPanel;

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
  int viewportWidth() const;
  int viewportHeight() const;
  // Where the viewport's top-left pixel lies in the window, as laid out by the last frame.
  int viewportX() const;
  int viewportY() const;
  render::RenderStyle& style();
  const render::RenderStyle& style() const;

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

  // Opens the dialog importing a garment or a mesh obstacle.
  void openImport(MeshImportDialog::Kind kind);

  // Where named items were drawn in the last frame, for scripts that click them (the point
  // {"item": NAME}): document fields by their path (a point inside the input box, which is the
  // item's left part), the left panel's tabs as "tab:scene", "tab:inspect", "tab:targets",
  // "tab:optimise", the timeline's buttons as "timeline:simulate", "timeline:start",
  // "timeline:play", "timeline:end" (their centres), a dialog's confirming button as
  // "dialog:confirm" and its file browser's items (FileBrowserView.h). Null when not drawn in
  // the last frame.
  const std::array<float, 2>* itemPoint(const std::string& name) const;
  const std::map<std::string, std::array<float, 2>>& itemPoints() const { return itemPoints_; }
  void noteItem(const std::string& name, float x, float y);
  // The last item ImGui drew, noted by `name` at its centre.
  void noteLastItem(const std::string& name);

  // The file browser of the open file or import dialog, null when none is open.
  const FileBrowser* openBrowser() const;

  // The solver's state as the timeline last drew it: its banner ("" for none) and the red
  // ticks of unconverged steps on its slider.
  const std::string& solverBanner() const;
  int unconvergedTicks() const;

  // Dear ImGui assertions this app has recovered from (ImGuiAssert.h): each is logged to stderr
  // with its file, line and expression, and the frame it broke ended through ImGui's recovery.
  int recoveredAssertions() const { return recoveredAssertions_; }
  // A check of that recovery: the next frame breaks ImGui's contract (a PopID without its
  // PushID, which Debian's libimgui.a asserts on).
  void provokeAssertion() { provokeAssertion_ = true; }

 private:
  void drawUi();
  void recover(const std::exception& failure);
  void drawMenuBar();
  void drawScenePanel(float top, float height);
  void drawFileDialog();
  void drawUnsavedPrompt();
  void drawRecoveryPrompt();
  void handleShortcuts();

  void doOpen(const std::string& file);
  void doSave();
  void doSaveAs(const std::string& file);
  void doUndo();
  void doRedo();

  EditorSession& session_;
  render::RenderContext& context_;
  std::unique_ptr<ViewportPanel> viewport_;
  std::unique_ptr<ScenePanel> scene_;
  std::unique_ptr<TimelinePanel> timeline_;
  std::unique_ptr<InspectorPanel> inspector_;
  std::unique_ptr<TargetPanel> targets_;
  std::unique_ptr<OptimiserPanel> optimiser_;
  std::unique_ptr<MeshImportDialog> importDialog_;
  PanelTab tab_ = PanelTab::Scene, requestedTab_ = PanelTab::Scene;
  bool tabRequested_ = false;

  enum class FileDialog { None, Open, SaveAs };
  FileDialog fileDialog_ = FileDialog::None;
  char pathBuffer_[1024] = {};
  FileBrowser sceneBrowser_{{".json"}};
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
  std::map<std::string, std::array<float, 2>> itemPoints_;
  int recoveredAssertions_ = 0;
  bool provokeAssertion_ = false;
  // What an earlier run's autosave left, offered once at start (Restore / Discard / Later).
  std::vector<Recovery> recoveries_;
  bool recoveryChecked_ = false;
};

}  // namespace weft::editor
