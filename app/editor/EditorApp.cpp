#include "EditorApp.h"

#include "EditorGl.h"
#include "FileBrowserView.h"
#include "ImGuiAssert.h"
#include "InspectorPanel.h"
#include "MeshImportDialog.h"
#include "ObstacleTemplates.h"
#include "OptimiserPanel.h"
#include "PanelStyle.h"
#include "ScenePanel.h"
#include "TargetPanel.h"
#include "TimelinePanel.h"
#include "ViewportPanel.h"

#include <weft/render/RenderError.h>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // GetTopMostPopupModal: whether a dialog is open, and which

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

namespace weft::editor {
namespace {

constexpr float kPanelWidth = 380.0f;
constexpr float kTimelineHeight = 150.0f;
// Alt must be up: Alt+Z is not Ctrl+Z, Alt+F not F (Alt is the target-drag modifier).
bool keyChord(bool ctrl, bool shift, int key) {
  const ImGuiIO& io = ImGui::GetIO();
  return io.KeyCtrl == ctrl && io.KeyShift == shift && !io.KeyAlt &&
         ImGui::IsKeyPressed(key, false);
}

// Logs what ImGui's error recovery repaired (a window left open, a PushID without its PopID...).
void logRecovery(void*, const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::fprintf(stderr, "weft-editor:   ");
  std::vfprintf(stderr, format, args);
  std::fprintf(stderr, "\n");
  va_end(args);
}

// GLFW's key codes for letters are their upper-case ASCII codes; ImGui 1.86 indexes
// io.KeysDown by the platform's codes.
// The cloth's opacity in the See-through cloth view.
constexpr float kSeeThroughOpacity = 0.45f;

constexpr int kKeyN = 'N', kKeyO = 'O', kKeyS = 'S', kKeyQ = 'Q', kKeyF = 'F', kKeyI = 'I',
              kKeyK = 'K';

}  // namespace

bool parsePanelTab(const std::string& text, PanelTab& tab) {
  if (text == "scene")
    tab = PanelTab::Scene;
  else if (text == "inspect")
    tab = PanelTab::Inspect;
  else if (text == "targets")
    tab = PanelTab::Targets;
  else if (text == "optimise" || text == "optimize")
    tab = PanelTab::Optimise;
  else
    return false;
  return true;
}

EditorApp::EditorApp(EditorSession& session, render::RenderContext& context)
    : session_(session), context_(context) {
  context_.makeCurrent();
  loadEditorGl(context_);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // fixed layout; nothing written next to the working directory
  ImGui::StyleColorsDark();
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw render::ContextError("Dear ImGui's OpenGL3 backend could not start");
  viewport_ = std::make_unique<ViewportPanel>(session_, *this, context_);
  scene_ = std::make_unique<ScenePanel>(session_, *this);
  timeline_ = std::make_unique<TimelinePanel>(session_, *this);
  inspector_ = std::make_unique<InspectorPanel>();
  targets_ = std::make_unique<TargetPanel>();
  optimiser_ = std::make_unique<OptimiserPanel>();
  importDialog_ = std::make_unique<MeshImportDialog>();
}

EditorApp::~EditorApp() {
  context_.makeCurrent();
  viewport_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
}

int EditorApp::viewportWidth() const {
  return viewport_->width();
}
int EditorApp::viewportHeight() const {
  return viewport_->height();
}
int EditorApp::viewportX() const {
  return viewport_->x();
}
int EditorApp::viewportY() const {
  return viewport_->y();
}
render::RenderStyle& EditorApp::style() {
  return viewport_->style();
}

const render::RenderStyle& EditorApp::style() const {
  return viewport_->style();
}

void EditorApp::report(const std::string& text, bool error) {
  message_ = text;
  messageIsError_ = error;
}

void EditorApp::frame() {
  context_.makeCurrent();
  ImGuiIO& io = ImGui::GetIO();
  session_.tick(io.DeltaTime);
  ImGui_ImplOpenGL3_NewFrame();
  itemPoints_.clear();
  ImGui::NewFrame();
  // A failed ImGui assertion throws (ImGuiAssert.h): the frame it broke is ended through ImGui's
  // recovery and drawn as far as it got; the next frame starts clean. A second failure while
  // ending the same frame is not recoverable and goes to the caller.
  try {
    drawUi();
  } catch (const ImGuiAssertion& failure) {
    recover(failure);
  }
  try {
    ImGui::Render();
  } catch (const ImGuiAssertion& failure) {
    recover(failure);
    ImGui::Render();
  }
  const WeftEditorGl& gl = weftEditorGl;
  context_.makeCurrent();
  gl.BindFramebuffer(GL_FRAMEBUFFER, context_.framebuffer());
  gl.Viewport(0, 0, context_.width(), context_.height());
  gl.ClearColor(0.10f, 0.10f, 0.12f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void EditorApp::recover(const std::exception& failure) {
  ++recoveredAssertions_;
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiWindow* window = g.CurrentWindow;
  // The context a report needs: where (the window being drawn, the tab), what the user was
  // working with (the active and hovered items), when (the frame). A failure repeating every
  // frame is logged ten times, then only counted (state imgui_assertions).
  constexpr int kLogged = 10;
  const bool log = recoveredAssertions_ <= kLogged;
  if (log)
    std::fprintf(stderr,
                 "weft-editor: recovered from %s (frame %d, window \"%s\", tab %d, active item "
                 "0x%08x, hovered item 0x%08x, dialog \"%s\")\n",
                 failure.what(), g.FrameCount, window ? window->Name : "", int(tab_), g.ActiveId,
                 g.HoveredId, modalDialog().c_str());
  if (recoveredAssertions_ == kLogged)
    std::fprintf(stderr, "weft-editor: further recoveries are counted, not logged\n");
  ImGui::ErrorCheckEndFrameRecover(log ? logRecovery : nullptr, nullptr);
  // The item that was being edited may be the one in a broken state: let go of it.
  ImGui::ClearActiveID();
  report(std::string("The interface recovered from an internal error (logged): ") + failure.what(),
         true);
}

void EditorApp::drawUi() {
  const ImGuiIO& io = ImGui::GetIO();
  handleShortcuts();
  drawMenuBar();
  const float top = ImGui::GetFrameHeight();  // below the main menu bar
  const float width = io.DisplaySize.x, height = io.DisplaySize.y;
  drawScenePanel(top, height - top);
  viewport_->draw(kPanelWidth, top, width - kPanelWidth, height - top - kTimelineHeight);
  timeline_->draw(kPanelWidth, height - kTimelineHeight, width - kPanelWidth, kTimelineHeight);
  drawFileDialog();
  importDialog_->draw(session_, *this);
  drawUnsavedPrompt();
  drawRecoveryPrompt();
}

const std::string& EditorApp::solverBanner() const {
  return timeline_->banner();
}
int EditorApp::unconvergedTicks() const {
  return timeline_->unconvergedTicks();
}

const std::array<float, 2>* EditorApp::itemPoint(const std::string& name) const {
  const auto it = itemPoints_.find(name);
  return it == itemPoints_.end() ? nullptr : &it->second;
}

void EditorApp::noteItem(const std::string& name, float x, float y) {
  itemPoints_[name] = {x, y};
}

const FileBrowser* EditorApp::openBrowser() const {
  if (fileDialog_ != FileDialog::None) return &sceneBrowser_;
  return importDialog_->browser();
}

void EditorApp::noteLastItem(const std::string& name) {
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  noteItem(name, 0.5f * (low.x + high.x), 0.5f * (low.y + high.y));
}

void EditorApp::handleShortcuts() {
  ImGuiIO& io = ImGui::GetIO();
  // A modal dialog (the close prompt, a file or import dialog) blocks the menus; it blocks their
  // shortcuts too, or they would act on the document behind it (Ctrl+N replacing the document
  // the close prompt asks about, Ctrl+Z undoing it).
  if (ImGui::GetTopMostPopupModal()) return;
  if (keyChord(true, false, kKeyN)) requestNew();
  if (keyChord(true, false, kKeyO)) fileDialog_ = FileDialog::Open;
  if (keyChord(true, false, kKeyS)) doSave();
  if (keyChord(true, true, kKeyS)) fileDialog_ = FileDialog::SaveAs;
  if (keyChord(true, false, kKeyQ)) requestClose();
  if (keyChord(true, false, kKeyI)) importDialog_->open(MeshImportDialog::Kind::Garment);
  if (io.WantTextInput) return;  // typing into a field: no single-key shortcuts, no undo
  if (keyChord(true, false, ImGui::GetKeyIndex(ImGuiKey_Z))) doUndo();
  if (keyChord(true, true, ImGui::GetKeyIndex(ImGuiKey_Z)) ||
      keyChord(true, false, ImGui::GetKeyIndex(ImGuiKey_Y)))
    doRedo();
  const int available = session_.timeline().frames();
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Space)))
    session_.timeline().togglePlayback();
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_RightArrow)))
    session_.playback().step(1, available);
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_LeftArrow)))
    session_.playback().step(-1, available);
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Home))) session_.timeline().goToStart();
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_End))) session_.timeline().goToEnd();
  if (keyChord(false, false, kKeyF)) session_.frameCamera(viewport_->aspect());
  if (keyChord(false, false, kKeyK) &&
      session_.placement().activeObject().kind == EditorObject::Kind::Handle) {
    const std::string error = session_.placement().setKey();
    report(error.empty() ? "key set" : error, !error.empty());
  }
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Escape)) && !viewport_->draggingGizmo())
    session_.placement().setActiveObject("");
}

void EditorApp::doOpen(const std::string& file) {
  try {
    session_.open(file);
    session_.frameCamera(viewport_->aspect());
    report("opened " + file, false);
  } catch (const std::exception& e) {
    report(e.what(), true);
  }
}

void EditorApp::doSave() {
  if (session_.document().file().empty()) {
    fileDialog_ = FileDialog::SaveAs;
    return;
  }
  try {
    const std::string warning = session_.save();
    report(warning.empty() ? "saved " + session_.document().file() : warning, !warning.empty());
  } catch (const std::exception& e) {
    report(e.what(), true);
  }
}

void EditorApp::doSaveAs(const std::string& file) {
  try {
    const std::string warning = session_.saveAs(file);
    report(warning.empty() ? "saved " + file : warning, !warning.empty());
  } catch (const std::exception& e) {
    report(e.what(), true);
  }
}

void EditorApp::doUndo() {
  const std::string label = session_.document().undoLabel();
  if (session_.document().undo()) report("undid: " + label, false);
}

void EditorApp::doRedo() {
  const std::string label = session_.document().redoLabel();
  if (session_.document().redo()) report("redid: " + label, false);
}

void EditorApp::requestClose() {
  askIfUnsaved(PendingAction::Close, "");
}
void EditorApp::requestNew() {
  askIfUnsaved(PendingAction::New, "");
}
void EditorApp::requestOpen(const std::string& file) {
  askIfUnsaved(PendingAction::Open, file);
}

void EditorApp::askIfUnsaved(PendingAction action, const std::string& file) {
  if (session_.document().dirty()) {
    pending_ = action;
    pendingFile_ = file;
  } else {
    carryOut(action, file);
  }
}

void EditorApp::carryOut(PendingAction action, const std::string& file) {
  switch (action) {
    case PendingAction::Close:
      closeConfirmed_ = true;
      break;
    case PendingAction::New:
      session_.newDocument();
      report("new document", false);
      break;
    case PendingAction::Open:
      doOpen(file);
      break;
    case PendingAction::None:
      break;
  }
}

std::string EditorApp::unsavedPrompt() const {
  switch (pending_) {
    case PendingAction::Close:
      return "close";
    case PendingAction::New:
      return "new";
    case PendingAction::Open:
      return "open";
    case PendingAction::None:
      break;
  }
  return "";
}

std::string EditorApp::modalDialog(float* rect) const {
  const ImGuiWindow* modal = ImGui::GetTopMostPopupModal();
  if (!modal) return "";
  if (rect) {
    rect[0] = modal->Pos.x, rect[1] = modal->Pos.y;
    rect[2] = modal->Size.x, rect[3] = modal->Size.y;
  }
  // A window's name is its title up to "##" (the rest only makes the id unique).
  const char* end = std::strstr(modal->Name, "##");
  return end ? std::string(modal->Name, std::size_t(end - modal->Name)) : std::string(modal->Name);
}

void EditorApp::openImport(MeshImportDialog::Kind kind) {
  importDialog_->open(kind);
}

void EditorApp::drawMenuBar() {
  if (!ImGui::BeginMainMenuBar()) return;
  EditorDocument& doc = session_.document();
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) requestNew();
    if (ImGui::MenuItem("Open...", "Ctrl+O")) fileDialog_ = FileDialog::Open;
    if (ImGui::BeginMenu("Open Recent", !session_.recent().files().empty())) {
      for (const std::string& f : session_.recent().files())
        if (ImGui::MenuItem(f.c_str())) requestOpen(f);
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Save", "Ctrl+S")) doSave();
    if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S")) fileDialog_ = FileDialog::SaveAs;
    ImGui::Separator();
    if (ImGui::MenuItem("Import garment...", "Ctrl+I"))
      importDialog_->open(MeshImportDialog::Kind::Garment);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) requestClose();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo = doc.canUndo() ? "Undo " + doc.undoLabel() : "Undo";
    const std::string redo = doc.canRedo() ? "Redo " + doc.redoLabel() : "Redo";
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, doc.canUndo())) doUndo();
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Y", false, doc.canRedo())) doRedo();
    ImGui::Separator();
    if (ImGui::MenuItem("Clear selection", nullptr, false, !session_.selection().empty()))
      session_.selection().clear();
    ImGui::Separator();
    // Not an action of its own (the click happens in the viewport): listed for its shortcut.
    ImGui::MenuItem("Gizmo: pick an obstacle or cloth", "Ctrl+Click", false, false);
    if (ImGui::MenuItem("Gizmo: off", "Esc", false,
                        session_.placement().activeObject().kind != EditorObject::Kind::None))
      session_.placement().setActiveObject("");
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Add")) {
    if (ImGui::MenuItem("Garment (mesh file)...", "Ctrl+I"))
      importDialog_->open(MeshImportDialog::Kind::Garment);
    ImGui::Separator();
    for (const std::string& shape : analyticObstacleShapes()) {
      const std::string label = "Obstacle: " + shape;
      if (ImGui::MenuItem(label.c_str())) {
        const std::string error =
            session_.additions().addObstacle(shape, session_.selection().nodes());
        report(error.empty() ? "added a " + shape + " (edit it under Obstacles)" : error,
               !error.empty());
        showTab(PanelTab::Scene);
      }
    }
    if (ImGui::MenuItem("Obstacle: mesh file..."))
      importDialog_->open(MeshImportDialog::Kind::Obstacle);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    const float aspect = viewport_->aspect();
    if (ImGui::MenuItem("Frame scene", "F")) session_.frameCamera(aspect);
    if (ImGui::MenuItem("Front")) session_.frameCamera(aspect, render::NamedView::Front);
    if (ImGui::MenuItem("Side")) session_.frameCamera(aspect, render::NamedView::Side);
    if (ImGui::MenuItem("Top")) session_.frameCamera(aspect, render::NamedView::Top);
    ImGui::Separator();
    ImGui::MenuItem("Wireframe", nullptr, &viewport_->style().wireframe);
    ImGui::MenuItem("Contact branch colours", nullptr, &session_.viewport().contactColours);
    ImGui::MenuItem("Contact force arrows", nullptr, &session_.viewport().forceArrows);
    ImGui::MenuItem("Legend", nullptr, &viewport_->style().legend);
    ImGui::Separator();
    // For a garment on a body: what the cloth covers shows through.
    bool seeThrough = viewport_->style().clothOpacity < 1.0f;
    if (ImGui::MenuItem("See-through cloth", nullptr, &seeThrough))
      viewport_->style().clothOpacity = seeThrough ? kSeeThroughOpacity : 1.0f;
    ImGui::MenuItem("Obstacles in front", nullptr, &viewport_->style().obstaclesInFront);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Panels")) {
    if (ImGui::MenuItem("Scene", nullptr, tab_ == PanelTab::Scene)) showTab(PanelTab::Scene);
    if (ImGui::MenuItem("Inspect (vertex, contacts, solver)", nullptr, tab_ == PanelTab::Inspect))
      showTab(PanelTab::Inspect);
    if (ImGui::MenuItem("Targets", nullptr, tab_ == PanelTab::Targets)) showTab(PanelTab::Targets);
    if (ImGui::MenuItem("Optimise", nullptr, tab_ == PanelTab::Optimise))
      showTab(PanelTab::Optimise);
    ImGui::EndMenu();
  }
  std::string title = doc.displayName() + (doc.dirty() ? " *" : "");
  ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(title.c_str()).x - 16.0f);
  ImGui::TextUnformatted(title.c_str());
  ImGui::EndMainMenuBar();
}

void EditorApp::drawScenePanel(float top, float height) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, height));
  ImGui::Begin("Scene", nullptr, kFixedWindow);
  if (provokeAssertion_) {
    provokeAssertion_ = false;
    ImGui::PopID();  // nothing pushed: ImGui asserts "Too many PopID()"
  }
  EditorDocument& doc = session_.document();
  ImGui::Text("%s%s", doc.displayName().c_str(), doc.dirty() ? " (unsaved changes)" : "");
  // The status (valid or why not, the loader's warnings, the last action's message) lives in a
  // box of fixed height, so that the panel below never moves when it changes; more than fits
  // scrolls inside the box, and hovering shows it all.
  std::string all;
  const float statusHeight = 3.0f * ImGui::GetTextLineHeightWithSpacing() + 4.0f;
  ImGui::BeginChild("status", ImVec2(0.0f, statusHeight), false);
  if (doc.valid()) {
    ImGui::TextColored(kOkColour, "Valid scene: %d vertices", doc.scene()->vertexCount());
    for (const std::string& w : doc.scene()->warnings) {
      ImGui::PushStyleColor(ImGuiCol_Text, kWarningColour);
      ImGui::TextWrapped("warning: %s", w.c_str());
      ImGui::PopStyleColor();
      all += "warning: " + w + "\n";
    }
  } else {
    // The loader's own message (file, JSON path, what is wrong); simulation waits for a fix.
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("error: %s", doc.validationError().c_str());
    ImGui::PopStyleColor();
    all += "error: " + doc.validationError() + "\n";
  }
  if (!message_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, messageIsError_
                                             ? kErrorColour
                                             : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
    all += message_;
  }
  ImGui::EndChild();
  if (!all.empty() && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
    ImGui::TextUnformatted(all.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  ImGui::Separator();
  ImGui::PushItemWidth(170.0f);
  if (ImGui::BeginTabBar("panels")) {
    const struct {
      const char* label;
      PanelTab tab;
      const char* item;
    } tabs[] = {{"Scene", PanelTab::Scene, "tab:scene"},
                {"Inspect", PanelTab::Inspect, "tab:inspect"},
                {"Targets", PanelTab::Targets, "tab:targets"},
                {"Optimise", PanelTab::Optimise, "tab:optimise"}};
    for (const auto& t : tabs) {
      const ImGuiTabItemFlags flags =
          tabRequested_ && requestedTab_ == t.tab ? ImGuiTabItemFlags_SetSelected : 0;
      const bool open = ImGui::BeginTabItem(t.label, nullptr, flags);
      noteLastItem(t.item);
      if (open) {
        tab_ = t.tab;
        switch (t.tab) {
          case PanelTab::Scene:
            scene_->draw();
            break;
          case PanelTab::Inspect:
            inspector_->draw(session_);
            break;
          case PanelTab::Targets:
            targets_->draw(session_, *this);
            break;
          case PanelTab::Optimise:
            optimiser_->draw(session_, *this);
            break;
        }
        ImGui::EndTabItem();
      }
    }
    tabRequested_ = false;
    ImGui::EndTabBar();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

render::Image EditorApp::viewportImage(int width, int height) {
  return viewport_->image(width, height);
}

render::Image EditorApp::windowImage() {
  context_.makeCurrent();
  const WeftEditorGl& gl = weftEditorGl;
  const int w = context_.width(), h = context_.height();
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w) * h * 4);
  gl.BindFramebuffer(GL_FRAMEBUFFER, context_.framebuffer());
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  render::Image image(w, h);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* src = &rgba[static_cast<std::size_t>(h - 1 - y) * w * 4];
    std::uint8_t* dst = image.at(0, y);
    for (int x = 0; x < w; ++x, src += 4, dst += 3)
      dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
  }
  return image;
}

void EditorApp::drawFileDialog() {
  if (fileDialog_ == FileDialog::None) return;
  const char* title = fileDialog_ == FileDialog::Open ? "Open scene" : "Save scene as";
  if (!ImGui::IsPopupOpen(title)) {
    const std::string current = session_.document().file();
    std::snprintf(pathBuffer_, sizeof pathBuffer_, "%s", current.c_str());
    ImGui::OpenPopup(title);
    if (!sceneBrowser_.showFolderOf(current)) sceneBrowser_.show(".");
  }
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("Scene file path (absolute, or relative to the working directory):");
    ImGui::SetNextItemWidth(520.0f);
    // The path is what the dialog is for: typing goes into it at once, without a click first.
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    bool enter = ImGui::InputText("##path", pathBuffer_, sizeof pathBuffer_,
                                  ImGuiInputTextFlags_EnterReturnsTrue);
    const FileBrowserEvent browsed = drawFileBrowser(
        sceneBrowser_, browsePlaces(session_.document().file(), session_.recent().files()),
        pathBuffer_, *this, 520.0f, 200.0f);
    if (browsed.kind == FileBrowserEvent::Kind::Picked ||
        browsed.kind == FileBrowserEvent::Kind::Confirmed) {
      std::snprintf(pathBuffer_, sizeof pathBuffer_, "%s", browsed.path.c_str());
      enter |= browsed.kind == FileBrowserEvent::Kind::Confirmed;
    } else if (browsed.kind == FileBrowserEvent::Kind::Moved && fileDialog_ == FileDialog::SaveAs) {
      // Save As keeps the name typed and puts it in the folder browsed to.
      const std::string name = std::filesystem::path(pathBuffer_).filename().string();
      if (!name.empty())
        std::snprintf(pathBuffer_, sizeof pathBuffer_, "%s",
                      (std::filesystem::path(browsed.path) / name).string().c_str());
    }
    const bool ok = ImGui::Button(fileDialog_ == FileDialog::Open ? "Open" : "Save") || enter;
    noteLastItem("dialog:confirm");
    ImGui::SameLine();
    // Esc cancels once the path field is let go (in it, Esc only leaves the field), as in the
    // import dialog.
    const bool cancel = ImGui::Button("Cancel") ||
                        (!ImGui::IsAnyItemActive() && !ImGui::IsWindowAppearing() &&
                         ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false));
    if (ok && pathBuffer_[0]) {
      if (fileDialog_ == FileDialog::Open) {
        requestOpen(pathBuffer_);
      } else {
        doSaveAs(pathBuffer_);
        // Saved for the unsaved-changes prompt: go on with what it asked about.
        if (!session_.document().dirty()) carryOut(afterSaveAs_, pendingFile_);
      }
    }
    if ((ok && pathBuffer_[0]) || cancel) {
      afterSaveAs_ = PendingAction::None;
      fileDialog_ = FileDialog::None;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void EditorApp::drawUnsavedPrompt() {
  if (pending_ == PendingAction::None) return;
  if (!ImGui::IsPopupOpen("Unsaved changes")) ImGui::OpenPopup("Unsaved changes");
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.", session_.document().displayName().c_str());
    const std::string before = pending_ == PendingAction::Close ? "closing"
                               : pending_ == PendingAction::New ? "starting a new scene"
                                                                : "opening " + pendingFile_;
    ImGui::Text("Save them before %s?", before.c_str());
    // Enter is the default (Save), Esc cancels, as in other desktop applications. Not in the
    // frame the prompt appears: the Enter that confirmed the Open dialog would save at once.
    const bool keys = !ImGui::IsWindowAppearing();
    const bool save = ImGui::Button("Save") ||
                      (keys && (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
                                keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_KeyPadEnter))));
    ImGui::SameLine();
    const bool discard = ImGui::Button("Discard");
    ImGui::SameLine();
    const bool cancel = ImGui::Button("Cancel") ||
                        (keys && keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Escape)));
    const PendingAction action = pending_;
    if (save || discard || cancel) {
      pending_ = PendingAction::None;
      ImGui::CloseCurrentPopup();
    }
    if (save) {
      doSave();
      if (!session_.document().dirty())
        carryOut(action, pendingFile_);
      else if (fileDialog_ == FileDialog::SaveAs)
        afterSaveAs_ = action;  // a new document has no file yet: Save As first
    } else if (discard) {
      session_.autosave().discardCurrent();  // dropped on purpose: nothing to recover
      carryOut(action, pendingFile_);
    }
    ImGui::EndPopup();
  }
}

void EditorApp::drawRecoveryPrompt() {
  if (!recoveryChecked_) {
    recoveryChecked_ = true;
    recoveries_ = session_.autosave().recoveries();
  }
  if (recoveries_.empty() || pending_ != PendingAction::None || fileDialog_ != FileDialog::None)
    return;
  const char* title = "Recover unsaved work";
  if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::TextUnformatted("An earlier session ended with unsaved changes, kept by the autosave:");
  int restore = -1, discard = -1;
  for (std::size_t k = 0; k < recoveries_.size(); ++k) {
    const Recovery& r = recoveries_[k];
    ImGui::PushID(static_cast<int>(k));
    ImGui::Text("%s (autosaved %s)", r.sceneFile.empty() ? "untitled" : r.sceneFile.c_str(),
                r.savedAt.c_str());
    if (ImGui::SmallButton("Restore")) restore = static_cast<int>(k);
    noteLastItem("recovery:restore:" + std::to_string(k));
    ImGui::SameLine();
    if (ImGui::SmallButton("Discard")) discard = static_cast<int>(k);
    noteLastItem("recovery:discard:" + std::to_string(k));
    ImGui::PopID();
  }
  const bool later = ImGui::Button("Later");
  ImGui::SameLine();
  ImGui::TextDisabled("(the files stay in %s)", session_.autosave().folder().c_str());
  if (restore >= 0) {
    const Recovery r = recoveries_[static_cast<std::size_t>(restore)];
    const std::string error = session_.restore(r);
    if (error.empty()) session_.frameCamera(viewport_->aspect());
    report(error.empty()
               ? "restored the unsaved changes of " +
                     (r.sceneFile.empty() ? std::string("an untitled scene") : r.sceneFile)
               : error,
           !error.empty());
    // One document at a time: the others wait for the next start.
    recoveries_.clear();
  } else if (discard >= 0) {
    Autosave::remove(recoveries_[static_cast<std::size_t>(discard)]);
    recoveries_.erase(recoveries_.begin() + discard);
  }
  if (later) recoveries_.clear();
  if (recoveries_.empty()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace weft::editor
