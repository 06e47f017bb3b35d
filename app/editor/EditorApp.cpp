#include "EditorApp.h"

#include "EditorGl.h"
#include "InspectorPanel.h"
#include "MeshImportDialog.h"
#include "ObstacleTemplates.h"
#include "OptimiserPanel.h"
#include "TargetPanel.h"
#include "ViewportTarget.h"

#include <weft/render/RenderError.h>
#include <weft/render/Renderer.h>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // GetTopMostPopupModal: whether a dialog is open, and which

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

namespace weft::editor {
namespace {

constexpr float kPanelWidth = 380.0f;
constexpr float kTimelineHeight = 150.0f;
constexpr ImGuiWindowFlags kFixedWindow = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                          ImGuiWindowFlags_NoCollapse |
                                          ImGuiWindowFlags_NoBringToFrontOnFocus;
const ImVec4 kErrorColour(0.95f, 0.35f, 0.30f, 1.0f);
const ImVec4 kWarningColour(0.95f, 0.75f, 0.25f, 1.0f);
const ImVec4 kOkColour(0.45f, 0.85f, 0.45f, 1.0f);

double numberAt(const EditorDocument& doc, const std::string& path, double fallback) {
  const nlohmann::json* v = doc.find(path);
  return v && v->is_number() ? v->get<double>() : fallback;
}

// Alt must be up: Alt+Z is not Ctrl+Z, Alt+F not F (Alt is the target-drag modifier).
bool keyChord(bool ctrl, bool shift, int key) {
  const ImGuiIO& io = ImGui::GetIO();
  return io.KeyCtrl == ctrl && io.KeyShift == shift && !io.KeyAlt &&
         ImGui::IsKeyPressed(key, false);
}

// GLFW's key codes for letters are their upper-case ASCII codes; ImGui 1.86 indexes
// io.KeysDown by the platform's codes.
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
  viewport_ = std::make_unique<ViewportTarget>(context_, 640, 480);
  renderer_ = std::make_unique<render::Renderer>(*viewport_);
  style_.legend = true;
  inspector_ = std::make_unique<InspectorPanel>();
  targets_ = std::make_unique<TargetPanel>();
  optimiser_ = std::make_unique<OptimiserPanel>();
  importDialog_ = std::make_unique<MeshImportDialog>();
}

EditorApp::~EditorApp() {
  context_.makeCurrent();
  renderer_.reset();
  viewport_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
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
  ImGui::NewFrame();

  handleShortcuts();
  drawMenuBar();
  const float top = ImGui::GetFrameHeight();  // below the main menu bar
  const float width = io.DisplaySize.x, height = io.DisplaySize.y;
  drawScenePanel(top, height - top);
  drawViewport(kPanelWidth, top, width - kPanelWidth, height - top - kTimelineHeight);
  drawTimeline(kPanelWidth, height - kTimelineHeight, width - kPanelWidth, kTimelineHeight);
  drawFileDialog();
  importDialog_->draw(session_, *this);
  drawUnsavedPrompt();

  ImGui::Render();
  const WeftEditorGl& gl = weftEditorGl;
  context_.makeCurrent();
  gl.BindFramebuffer(GL_FRAMEBUFFER, context_.framebuffer());
  gl.Viewport(0, 0, context_.width(), context_.height());
  gl.ClearColor(0.10f, 0.10f, 0.12f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
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
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Space))) togglePlayback();
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_RightArrow)))
    session_.playback().step(1, available);
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_LeftArrow)))
    session_.playback().step(-1, available);
  if (keyChord(false, false, kKeyF))
    session_.frameCamera(float(viewportWidth_) / float(std::max(viewportHeight_, 1)));
  if (keyChord(false, false, kKeyK) &&
      session_.placement().activeObject().kind == EditorObject::Kind::Handle) {
    const std::string error = session_.placement().setKey();
    report(error.empty() ? "key set" : error, !error.empty());
  }
  if (keyChord(false, false, ImGui::GetKeyIndex(ImGuiKey_Escape)) && !draggingGizmo_)
    session_.placement().setActiveObject("");
}

void EditorApp::togglePlayback() {
  // Play at the last state starts again from the first: playing on from the end would stop at
  // once. A growing cache is left alone (its end is not the end).
  Playback& playback = session_.playback();
  const int available = session_.cache().frameCount();
  if (!playback.playing() && playback.frame() >= available - 1 && !session_.cache().running())
    playback.scrub(0, available);
  playback.toggle();
}

void EditorApp::doOpen(const std::string& file) {
  try {
    session_.open(file);
    session_.frameCamera(float(viewportWidth_) / float(std::max(viewportHeight_, 1)));
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
        const std::string error = session_.additions().addObstacle(shape);
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
    const float aspect = float(viewportWidth_) / float(std::max(viewportHeight_, 1));
    if (ImGui::MenuItem("Frame scene", "F")) session_.frameCamera(aspect);
    if (ImGui::MenuItem("Front")) session_.frameCamera(aspect, render::NamedView::Front);
    if (ImGui::MenuItem("Side")) session_.frameCamera(aspect, render::NamedView::Side);
    if (ImGui::MenuItem("Top")) session_.frameCamera(aspect, render::NamedView::Top);
    ImGui::Separator();
    ImGui::MenuItem("Wireframe", nullptr, &style_.wireframe);
    ImGui::MenuItem("Contact branch colours", nullptr, &session_.viewport().contactColours);
    ImGui::MenuItem("Contact force arrows", nullptr, &session_.viewport().forceArrows);
    ImGui::MenuItem("Legend", nullptr, &style_.legend);
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

void EditorApp::applyEdit(const std::string& error, unsigned itemId) {
  if (!error.empty()) report(error, true);
  lastEditId_ = itemId;
}

template <class Value, class Widget>
bool EditorApp::documentField(const char* label, const std::string& path, Value value,
                              Widget&& widget) {
  // One document edit per change; consecutive changes of the same item (typing, dragging) merge
  // into one undo step.
  ImGui::PushID(path.c_str());
  const ImGuiID id = ImGui::GetID(label);
  const bool changed = widget(&value);
  if (changed) {
    const bool coalesce = id == lastEditId_ && !ImGui::IsItemActivated();
    applyEdit(session_.document().setValue(path, value, coalesce), id);
  }
  if (ImGui::IsItemDeactivated()) lastEditId_ = 0;
  ImGui::PopID();
  return changed;
}

bool EditorApp::numberField(const char* label, const std::string& path, double fallback,
                            const char* format) {
  return documentField(label, path, numberAt(session_.document(), path, fallback),
                       [&](double* v) { return ImGui::InputDouble(label, v, 0.0, 0.0, format); });
}

bool EditorApp::integerField(const char* label, const std::string& path, int fallback) {
  return documentField(label, path, static_cast<int>(numberAt(session_.document(), path, fallback)),
                       [&](int* v) { return ImGui::InputInt(label, v); });
}

bool EditorApp::vectorField(const char* label, const std::string& path, const double* fallback) {
  double v[3] = {fallback[0], fallback[1], fallback[2]};
  const nlohmann::json* j = session_.document().find(path);
  if (j && j->is_array() && j->size() == 3)
    for (int i = 0; i < 3; ++i)
      if ((*j)[std::size_t(i)].is_number()) v[i] = (*j)[std::size_t(i)].get<double>();
  ImGui::PushID(path.c_str());
  const ImGuiID id = ImGui::GetID(label);
  const bool changed =
      ImGui::InputScalarN(label, ImGuiDataType_Double, v, 3, nullptr, nullptr, "%.4g");
  if (changed) {
    const bool coalesce = id == lastEditId_ && !ImGui::IsItemActivated();
    applyEdit(
        session_.document().setValue(path, nlohmann::json::array({v[0], v[1], v[2]}), coalesce),
        id);
  }
  if (ImGui::IsItemDeactivated()) lastEditId_ = 0;
  ImGui::PopID();
  return changed;
}

void EditorApp::comboField(const char* label, const std::string& path, const char* const* options,
                           int count, const char* fallback) {
  const nlohmann::json* j = session_.document().find(path);
  const std::string current = j && j->is_string() ? j->get<std::string>() : fallback;
  ImGui::PushID(path.c_str());
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (int i = 0; i < count; ++i)
      if (ImGui::Selectable(options[i], current == options[i]) && current != options[i])
        applyEdit(session_.document().setValue(path, options[i]));
    ImGui::EndCombo();
  }
  ImGui::PopID();
}

void EditorApp::drawScenePanel(float top, float height) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, height));
  ImGui::Begin("Scene", nullptr, kFixedWindow);
  EditorDocument& doc = session_.document();
  ImGui::Text("%s%s", doc.displayName().c_str(), doc.dirty() ? " (unsaved changes)" : "");
  if (doc.valid()) {
    ImGui::TextColored(kOkColour, "Valid scene: %d vertices", doc.scene()->vertexCount());
    for (const std::string& w : doc.scene()->warnings) {
      ImGui::PushStyleColor(ImGuiCol_Text, kWarningColour);
      ImGui::TextWrapped("warning: %s", w.c_str());
      ImGui::PopStyleColor();
    }
  } else {
    // The loader's own message (file, JSON path, what is wrong); simulation waits for a fix.
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("error: %s", doc.validationError().c_str());
    ImGui::PopStyleColor();
  }
  if (!message_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, messageIsError_
                                             ? kErrorColour
                                             : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::Separator();
  ImGui::PushItemWidth(170.0f);
  if (ImGui::BeginTabBar("panels")) {
    const struct {
      const char* label;
      PanelTab tab;
    } tabs[] = {{"Scene", PanelTab::Scene},
                {"Inspect", PanelTab::Inspect},
                {"Targets", PanelTab::Targets},
                {"Optimise", PanelTab::Optimise}};
    for (const auto& t : tabs) {
      const ImGuiTabItemFlags flags =
          tabRequested_ && requestedTab_ == t.tab ? ImGuiTabItemFlags_SetSelected : 0;
      if (ImGui::BeginTabItem(t.label, nullptr, flags)) {
        tab_ = t.tab;
        switch (t.tab) {
          case PanelTab::Scene:
            sceneTab();
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

void EditorApp::sceneTab() {
  if (ImGui::CollapsingHeader("Time step and solver", ImGuiTreeNodeFlags_DefaultOpen)) timePanel();
  if (ImGui::CollapsingHeader("Cloth and material", ImGuiTreeNodeFlags_DefaultOpen)) clothPanel();
  if (ImGui::CollapsingHeader("Gravity and wind")) effectsPanel();
  if (ImGui::CollapsingHeader("Obstacles")) obstaclePanel();
  if (ImGui::CollapsingHeader("Selection", ImGuiTreeNodeFlags_DefaultOpen)) selectionPanel();
}

void EditorApp::timePanel() {
  numberField("dt (s)", "time.dt", 0.01);
  integerField("steps", "time.steps", 100);
  static const char* methods[] = {"newton", "pd"};
  comboField("method", "solver.method", methods, 2, "newton");
  integerField("PD iterations", "solver.pd_iterations", 100);
  numberField("PD tolerance (m/s^2)", "solver.pd_tolerance", 1e-4);
  static const char* accelerations[] = {"anderson", "none"};
  comboField("acceleration", "solver.acceleration", accelerations, 2, "anderson");
}

void EditorApp::clothPanel() {
  const nlohmann::json* cloths = session_.document().find("cloths");
  if (!cloths || !cloths->is_array()) {
    ImGui::TextDisabled("no cloths");
    return;
  }
  for (std::size_t c = 0; c < cloths->size(); ++c) {
    const std::string base = "cloths." + std::to_string(c);
    ImGui::PushID(int(c));
    const bool open = ImGui::TreeNodeEx("cloth", ImGuiTreeNodeFlags_DefaultOpen, "Cloth %zu", c);
    ImGui::SameLine();
    placeButton(base);
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      // The cloths after it are numbered down, and `cloths` changes: stop drawing this frame.
      applyEdit(session_.document().removeValue(base));
      if (open) ImGui::TreePop();
      ImGui::PopID();
      return;
    }
    if (open) {
      static const double zero[3] = {0, 0, 0};
      if (const nlohmann::json* file = session_.document().find(base + ".mesh.file")) {
        ImGui::TextDisabled("mesh: %s", file->is_string() ? file->get<std::string>().c_str() : "?");
        numberField("scale", base + ".mesh.scale", 1.0);
      } else if (session_.document().find(base + ".mesh.grid")) {
        const nlohmann::json* size = session_.document().find(base + ".mesh.grid.size");
        const nlohmann::json* res = session_.document().find(base + ".mesh.grid.resolution");
        ImGui::TextDisabled("grid %s m, %s quads", size ? size->dump().c_str() : "?",
                            res ? res->dump().c_str() : "?");
      }
      if (ImGui::TreeNode("placement", "placement (mesh.transform)")) {
        vectorField("rotate (deg)", base + ".mesh.transform.rotate_deg", zero);
        vectorField("translate (m)", base + ".mesh.transform.translate", zero);
        ImGui::TreePop();
      }
      numberField("density (kg/m^2)", base + ".material.density", 0.1);
      numberField("stretch (N/m)", base + ".material.stretch", 100.0);
      numberField("bend (N m)", base + ".material.bend", 0.0);
      const bool hasSelf = session_.document().find(base + ".self_collision") != nullptr;
      bool self = hasSelf;
      if (ImGui::Checkbox("self-collision", &self)) {
        if (self)
          applyEdit(session_.document().setValue(base + ".self_collision",
                                                 {{"radius", 0.004}, {"friction", 0.3}}));
        else
          applyEdit(session_.document().removeValue(base + ".self_collision"));
      }
      if (hasSelf) {
        numberField("radius (m)", base + ".self_collision.radius", 0.004);
        numberField("friction", base + ".self_collision.friction", 0.3);
      }
      const nlohmann::json* attachments = session_.document().find(base + ".attachments");
      if (attachments && attachments->is_array()) {
        for (std::size_t a = 0; a < attachments->size(); ++a) {
          const nlohmann::json& at = (*attachments)[a];
          const std::size_t n =
              at.contains("vertices") && at["vertices"].is_array() ? at["vertices"].size() : 0;
          const std::string kind = at.value("kind", std::string("fixed"));
          ImGui::PushID(int(a));
          ImGui::Text("attachment %zu: %s, %zu vertices", a, kind.c_str(), n);
          if (kind == "handle") {
            ImGui::SameLine();
            placeButton(base + ".attachments." + std::to_string(a));
          }
          ImGui::SameLine();
          if (ImGui::SmallButton("remove"))
            applyEdit(session_.document().removeValue(base + ".attachments." + std::to_string(a)));
          ImGui::PopID();
        }
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void EditorApp::effectsPanel() {
  EditorDocument& doc = session_.document();
  bool gravity = doc.find("gravity") != nullptr;
  if (ImGui::Checkbox("gravity", &gravity)) {
    applyEdit(gravity ? doc.setValue("gravity", nlohmann::json::array({0.0, -9.8, 0.0}))
                      : doc.removeValue("gravity"));
  }
  if (doc.find("gravity")) {
    static const double g[3] = {0.0, -9.8, 0.0};
    vectorField("g (m/s^2)", "gravity", g);
  }
  bool wind = doc.find("wind") != nullptr;
  if (ImGui::Checkbox("wind", &wind)) {
    applyEdit(wind ? doc.setValue("wind", {{"direction", {1.0, 0.0, 0.0}},
                                           {"strength", 1.0},
                                           {"frequency", 1.0},
                                           {"phase", 0.0}})
                   : doc.removeValue("wind"));
  }
  if (doc.find("wind")) {
    static const double x[3] = {1.0, 0.0, 0.0};
    vectorField("direction", "wind.direction", x);
    // With a falloff centre (DiffCloth Eq. 35) the per-vertex factor is an inverse distance (1/m)
    // instead of an area (m^2), so strength is in N m instead of a pressure.
    const bool falloff = doc.find("wind.falloff") != nullptr;
    numberField(falloff ? "strength (N m, falloff)" : "strength (N/m^2)", "wind.strength", 0.0);
    if (falloff) {
      static const double origin[3] = {0.0, 0.0, 0.0};
      vectorField("falloff centre (m)", "wind.falloff.center", origin);
    }
    numberField("frequency (Hz)", "wind.frequency", 0.0);
    numberField("phase (rad)", "wind.phase", 0.0);
    static const char* models[] = {"sinusoid", "constant"};
    comboField("model", "wind.model", models, 2, "sinusoid");
  }
  ImGui::TextDisabled("Adding or removing an effect adds or removes its module.");
}

void EditorApp::obstaclePanel() {
  EditorDocument& doc = session_.document();
  const nlohmann::json* obstacles = doc.find("obstacles");
  const std::size_t count = obstacles && obstacles->is_array() ? obstacles->size() : 0;
  for (std::size_t i = 0; i < count; ++i) {
    const nlohmann::json& o = (*obstacles)[i];
    std::string shape = "?";
    for (const char* s : {"plane", "sphere", "capsule", "box", "cylinder", "mesh"})
      if (o.contains(s)) shape = s;
    const std::string base = "obstacles." + std::to_string(i);
    ImGui::PushID(int(i));
    const bool open =
        ImGui::TreeNodeEx("obstacle", ImGuiTreeNodeFlags_DefaultOpen, "%zu: %s", i, shape.c_str());
    ImGui::SameLine();
    placeButton(base);
    ImGui::SameLine();
    bool removed = false;
    if (ImGui::SmallButton("remove")) {
      applyEdit(doc.removeValue(base));
      removed = true;
    }
    if (open) {
      if (!removed) {
        static const double zero[3] = {0, 0, 0}, up[3] = {0, 1, 0}, one[3] = {1, 1, 1};
        const std::string s = base + "." + shape;
        if (shape == "plane") {
          vectorField("point", s + ".point", zero);
          vectorField("normal", s + ".normal", up);
        } else if (shape == "sphere") {
          vectorField("center", s + ".center", zero);
          numberField("radius", s + ".radius", 0.3);
        } else if (shape == "capsule" || shape == "cylinder") {
          vectorField("a", s + ".a", zero);
          vectorField("b", s + ".b", up);
          numberField("radius", s + ".radius", 0.1);
        } else if (shape == "box") {
          vectorField("center", s + ".center", zero);
          vectorField("size", s + ".size", one);
          vectorField("rotate (deg)", s + ".rotate_deg", zero);
        } else if (shape == "mesh") {
          const nlohmann::json* file = doc.find(s + ".file");
          ImGui::TextDisabled("mesh file: %s",
                              file && file->is_string() ? file->get<std::string>().c_str() : "?");
          numberField("scale", s + ".scale", 1.0);
          vectorField("rotate (deg)", s + ".transform.rotate_deg", zero);
          vectorField("translate (m)", s + ".transform.translate", zero);
        }
        numberField("friction", base + ".friction", 0.0);
        numberField("thickness (m)", base + ".thickness", 1e-3);
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
    if (removed) break;  // indices shifted; the list is drawn again next frame
  }
  ImGui::TextUnformatted("Add:");
  for (const std::string& shape : analyticObstacleShapes()) {
    ImGui::SameLine();
    if (ImGui::SmallButton(shape.c_str())) applyEdit(session_.additions().addObstacle(shape));
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("mesh...")) importDialog_->open(MeshImportDialog::Kind::Obstacle);
}

void EditorApp::placeButton(const std::string& path) {
  // Toggles which object the viewport's gizmo places; the active one's button is orange (one
  // label for both states keeps the attachment rows inside the panel).
  const bool active = session_.placement().activeObject().path() == path;
  ImGui::PushID(("place " + path).c_str());
  if (active) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.60f, 0.10f, 1.0f));
  if (ImGui::SmallButton("gizmo")) {
    const std::string error = session_.placement().setActiveObject(active ? "" : path);
    if (!error.empty()) report(error, true);
  }
  if (active) ImGui::PopStyleColor();
  ImGui::PopID();
}

void EditorApp::selectionPanel() {
  const auto& nodes = session_.selection().nodes();
  ImGui::Text("%zu vertices selected", nodes.size());
  if (!nodes.empty()) {
    std::string list;
    for (std::size_t i = 0; i < nodes.size() && i < 24; ++i)
      list += (i ? ", " : "") + std::to_string(nodes[i]);
    if (nodes.size() > 24) list += ", ...";
    ImGui::TextWrapped("%s", list.c_str());
  }
  ImGui::BeginDisabled(nodes.empty() || !session_.document().valid());
  if (ImGui::Button("Pin selection")) {
    const std::string error = session_.selecting().pinSelection();
    report(error.empty() ? "pinned " + std::to_string(nodes.size()) + " vertices" : error,
           !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Make handle")) {
    const std::string error = session_.selecting().makeHandle();
    report(error.empty() ? "made a handle of " + std::to_string(nodes.size()) +
                               " vertices: drag it with the gizmo, then Set key on the timeline"
                         : error,
           !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Clear")) session_.selection().clear();
  ImGui::EndDisabled();
  // By region: the border loop through the inspected vertex, or a band along an axis.
  ImGui::BeginDisabled(session_.selection().focus() < 0);
  if (ImGui::Button("Select its border loop")) {
    const std::string error = session_.selecting().selectBoundaryLoop(ImGui::GetIO().KeyShift);
    report(error.empty() ? "selected the border loop: " + std::to_string(nodes.size()) + " vertices"
                         : error,
           !error.empty());
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("The border (waist, hem, cuff) through the vertex last clicked; Shift adds.");
  static const char* axes[] = {"x", "y", "z"};
  ImGui::SetNextItemWidth(50.0f);
  ImGui::Combo("##band axis", &bandAxis_, axes, 3);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(150.0f);
  ImGui::InputScalarN("##band", ImGuiDataType_Double, band_, 2, nullptr, nullptr, "%.3f");
  ImGui::SameLine();
  ImGui::BeginDisabled(!session_.document().valid());
  if (ImGui::Button("Select band")) {
    const std::string error =
        session_.selecting().selectBand(bandAxis_, band_[0], band_[1], ImGui::GetIO().KeyShift);
    report(error.empty() ? "selected " + std::to_string(nodes.size()) + " vertices in the band"
                         : error,
           !error.empty());
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The vertices whose coordinate (as shown) lies between the two values, in metres; Shift "
        "adds.");
  ImGui::TextDisabled("Click: pick (and inspect) a vertex; drag: box");
  ImGui::TextDisabled("select; Shift adds. Right drag: orbit; middle:");
  ImGui::TextDisabled("pan; wheel: zoom; F: frame the scene; Alt+drag:");
  ImGui::TextDisabled("move the selected vertices' targets. Ctrl+click");
  ImGui::TextDisabled("an obstacle or cloth (or \"gizmo\" under");
  ImGui::TextDisabled("Obstacles, Cloth) to place it: drag the");
  ImGui::TextDisabled("gizmo's arrows and rings; Esc takes it off.");
}

void EditorApp::drawViewport(float left, float top, float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(left, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  // No background: the image covers the whole window, and on a software GL every filled pixel
  // counts.
  ImGui::Begin("Viewport", nullptr,
               kFixedWindow | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoBackground);
  ImGui::PopStyleVar();
  const ImVec2 size = ImGui::GetContentRegionAvail();
  viewportWidth_ = std::max(1, int(size.x));
  viewportHeight_ = std::max(1, int(size.y));
  renderViewport();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  // The picture is opaque: drawn without blending, which on a software GL saves reading back
  // every pixel under it (Dear ImGui blends everything it draws; the reset callback restores its
  // state for what follows).
  ImDrawList* drawList = ImGui::GetWindowDrawList();
  drawList->AddCallback([](const ImDrawList*, const ImDrawCmd*) { weftEditorGl.Disable(GL_BLEND); },
                        nullptr);
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(viewport_->colorTexture())),
               ImVec2(float(viewportWidth_), float(viewportHeight_)), ImVec2(0, 1), ImVec2(1, 0));
  drawList->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  ImGui::SetCursorScreenPos(origin);
  ImGui::InvisibleButton("viewport-input", ImVec2(float(viewportWidth_), float(viewportHeight_)),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const ImGuiIO& io = ImGui::GetIO();
  const bool hovered = ImGui::IsItemHovered();
  const ImVec2 mouse(io.MousePos.x - origin.x, io.MousePos.y - origin.y);
  viewportX_ = int(origin.x);
  viewportY_ = int(origin.y);
  render::Camera& camera = session_.camera();
  // The gizmo comes first: a press on one of its handles drags it rather than selecting.
  const GizmoHandle hoveredHandle =
      hovered && !draggingGizmo_
          ? session_.placement().pickGizmo(mouse.x, mouse.y, viewportWidth_, viewportHeight_)
          : GizmoHandle::None;
  if (hovered && io.MouseWheel != 0.0f) camera.zoom(std::pow(0.9f, io.MouseWheel));
  // Orbit and pan follow every pixel of the drag: IsMouseDragging would hold them back until
  // ImGui's 6 px drag threshold and drop the motion before it (these buttons have no click to
  // tell apart from a drag). The press frame's delta is the way the mouse came, not the drag.
  const bool dragging = ImGui::IsItemActive() && !ImGui::IsItemActivated();
  if (dragging && ImGui::IsMouseDown(ImGuiMouseButton_Right))
    camera.orbit(-io.MouseDelta.x * 0.4f, io.MouseDelta.y * 0.4f);
  if (dragging && ImGui::IsMouseDown(ImGuiMouseButton_Middle)) {
    const float scale = camera.distance * 2.0f * std::tan(camera.fovYDeg * 3.14159265f / 360.0f) /
                        float(viewportHeight_);
    camera.pan(-io.MouseDelta.x * scale, io.MouseDelta.y * scale);
  }
  if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    if (hoveredHandle != GizmoHandle::None) {
      const std::string error = session_.placement().beginGizmoDrag(
          hoveredHandle, mouse.x, mouse.y, viewportWidth_, viewportHeight_);
      if (error.empty())
        draggingGizmo_ = true;
      else
        report(error, true);
    } else if (io.KeyAlt && !session_.targets().all().empty()) {
      // Alt + drag moves the selected vertices' targets in the view plane (one undo step).
      draggingTargets_ = true;
      ++dragCount_;
      targetDragLast_[0] = mouse.x;
      targetDragLast_[1] = mouse.y;
    } else {
      boxStart_[0] = mouse.x;
      boxStart_[1] = mouse.y;
      boxSelecting_ = true;
    }
  }
  if (draggingTargets_) {
    // Measured from where the button went down, not by the frame's mouse delta: the press frame's
    // delta is the way the mouse came, which is no part of the drag.
    const float dx = mouse.x - targetDragLast_[0], dy = mouse.y - targetDragLast_[1];
    if (dx != 0.0f || dy != 0.0f) {
      targetDragLast_[0] = mouse.x;
      targetDragLast_[1] = mouse.y;
      const std::string error = session_.targets().dragTargets(
          session_.selection().nodes(), dx, dy, viewportWidth_, viewportHeight_,
          "target drag " + std::to_string(dragCount_));
      if (!error.empty()) report(error, true), draggingTargets_ = false;
    }
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) draggingTargets_ = false;
  }
  if (draggingGizmo_) {
    if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f) {
      const std::string error = session_.placement().dragGizmo(mouse.x, mouse.y);
      if (!error.empty()) report(error, true);
    }
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) ||
        session_.placement().draggedHandle() == GizmoHandle::None) {
      session_.placement().endGizmoDrag();
      draggingGizmo_ = false;
    }
  }
  ImDrawList* draw = ImGui::GetWindowDrawList();
  if (boxSelecting_) {
    const bool dragged = ImGui::IsMouseDragging(ImGuiMouseButton_Left);
    if (dragged)
      draw->AddRect(ImVec2(origin.x + boxStart_[0], origin.y + boxStart_[1]), io.MousePos,
                    IM_COL32(255, 210, 60, 255));
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
      boxSelecting_ = false;
      const ImVec2 drag = ImGui::GetMouseDragDelta(ImGuiMouseButton_Left);
      if (drag.x != 0.0f || drag.y != 0.0f)
        session_.selecting().boxSelectPixels(boxStart_[0], boxStart_[1], mouse.x, mouse.y,
                                             viewportWidth_, viewportHeight_, io.KeyShift);
      else if (io.KeyCtrl)
        pickObjectAt(mouse.x, mouse.y);
      else
        session_.selecting().clickSelect(mouse.x, mouse.y, viewportWidth_, viewportHeight_,
                                         io.KeyShift);
    }
  }
  // Selected vertices and lines to their targets, drawn over the image (not part of viewport
  // screenshots).
  if (const render::RenderScene* scene = session_.viewport().scene()) {
    for (const FinalTarget& t : session_.targets().all()) {
      if (t.node >= scene->cloth.positions.rows()) continue;
      const auto from = projectToPixel(camera, scene->cloth.positions.row(t.node).transpose(),
                                       viewportWidth_, viewportHeight_);
      const auto to =
          projectToPixel(camera, t.position.cast<float>(), viewportWidth_, viewportHeight_);
      if (from && to)
        draw->AddLine(ImVec2(origin.x + from->x(), origin.y + from->y()),
                      ImVec2(origin.x + to->x(), origin.y + to->y()), IM_COL32(160, 80, 200, 220),
                      1.5f);
    }
    for (int node : session_.selection().nodes()) {
      if (node >= scene->cloth.positions.rows()) continue;
      const auto p = projectToPixel(camera, scene->cloth.positions.row(node).transpose(),
                                    viewportWidth_, viewportHeight_);
      if (!p) continue;
      const ImVec2 at(origin.x + p->x(), origin.y + p->y());
      draw->AddCircleFilled(at, 4.0f, IM_COL32(255, 210, 60, 255));
      // The inspected vertex gets a ring: its dot alone looks like a slip-branch vertex.
      if (node == session_.selection().focus()) {
        draw->AddCircle(at, 9.0f, IM_COL32(20, 20, 24, 255), 0, 4.0f);
        draw->AddCircle(at, 9.0f, IM_COL32(255, 255, 255, 255), 0, 2.0f);
      }
    }
  }
  drawGizmo(draw, origin.x, origin.y, hoveredHandle);
  if (!session_.document().valid())
    draw->AddText(
        ImVec2(origin.x + 10, origin.y + 10), IM_COL32(230, 80, 70, 255),
        "The scene does not validate: showing the last valid state (see the Scene panel).");
  ImGui::End();
}

void EditorApp::pickObjectAt(float x, float y) {
  const std::string error = session_.placement().clickObject(x, y, viewportWidth_, viewportHeight_);
  const std::string picked = session_.placement().activeObject().path();
  if (!error.empty())
    report(error, true);
  else
    report(picked.empty() ? "nothing there: gizmo off" : "gizmo on " + picked, false);
}

void EditorApp::drawGizmo(ImDrawList* draw, float originX, float originY, GizmoHandle hovered) {
  const auto gizmo = session_.placement().gizmo(viewportWidth_, viewportHeight_);
  if (!gizmo) return;
  const GizmoHandle active = session_.placement().draggedHandle() != GizmoHandle::None
                                 ? session_.placement().draggedHandle()
                                 : hovered;
  const ImU32 axisColours[3] = {IM_COL32(225, 60, 50, 255), IM_COL32(60, 175, 60, 255),
                                IM_COL32(50, 100, 230, 255)};
  const ImU32 highlight = IM_COL32(255, 200, 40, 255), outline = IM_COL32(20, 20, 24, 200);
  auto at = [&](const Eigen::Vector2f& p) { return ImVec2(originX + p.x(), originY + p.y()); };
  // Rings under the arrows; every handle has a dark outline so it reads on light and dark.
  for (GizmoHandle h :
       {GizmoHandle::RotateX, GizmoHandle::RotateY, GizmoHandle::RotateZ, GizmoHandle::TranslateX,
        GizmoHandle::TranslateY, GizmoHandle::TranslateZ}) {
    if (!gizmo->has(h)) continue;
    const std::vector<Eigen::Vector2f> line = gizmo->screenPolyline(h);
    if (line.size() < 2) continue;
    const ImU32 colour = h == active ? highlight : axisColours[gizmoAxis(h)];
    std::vector<ImVec2> points;
    for (const Eigen::Vector2f& p : line) points.push_back(at(p));
    const bool ring = isRotation(h);
    draw->AddPolyline(points.data(), int(points.size()), outline, 0, ring ? 4.5f : 5.5f);
    draw->AddPolyline(points.data(), int(points.size()), colour, 0, ring ? 2.5f : 3.5f);
    if (!ring) {
      // The arrow head, in screen space along the shaft's image.
      const Eigen::Vector2f tip = line.back(), along = line.back() - line.front();
      if (along.norm() > 1.0f) {
        const Eigen::Vector2f d = along.normalized(), n(-d.y(), d.x());
        const Eigen::Vector2f base = tip - 12.0f * d;
        draw->AddTriangleFilled(at(tip + 3.0f * d), at(base + 6.5f * n), at(base - 6.5f * n),
                                outline);
        draw->AddTriangleFilled(at(tip), at(base + 5.0f * n), at(base - 5.0f * n), colour);
      }
    }
  }
  if (const auto centre =
          projectToPixel(session_.camera(), gizmo->origin(), viewportWidth_, viewportHeight_)) {
    draw->AddCircleFilled(at(*centre), 4.5f, outline);
    draw->AddCircleFilled(at(*centre), 3.0f, IM_COL32(250, 250, 250, 255));
  }
}

bool EditorApp::ViewportState::operator==(const ViewportState& o) const {
  return frameVersion == o.frameVersion && width == o.width && height == o.height &&
         std::equal(camera, camera + 11, o.camera) && wireframe == o.wireframe &&
         legend == o.legend && groundGrid == o.groundGrid;
}

void EditorApp::renderViewport() {
  viewport_->resize(viewportWidth_, viewportHeight_);
  const render::RenderScene* scene = session_.viewport().scene();
  const render::Camera& c = session_.camera();
  ViewportState now;
  now.frameVersion = session_.viewport().version();
  now.width = viewportWidth_;
  now.height = viewportHeight_;
  const float camera[11] = {
      c.target.x(),      c.target.y(), c.target.z(), c.distance,
      c.yawDeg,          c.pitchDeg,   c.fovYDeg,    c.orthographic ? 1.0f : 0.0f,
      c.orthoHalfHeight, c.nearPlane,  c.farPlane};
  std::copy(camera, camera + 11, now.camera);
  now.wireframe = style_.wireframe;
  now.legend = style_.legend;
  now.groundGrid = style_.groundGrid;
  // An unchanged picture is not drawn again (the texture keeps it): on a software GL the
  // viewport is most of a frame's cost.
  if (now == drawn_) return;
  render::RenderScene empty;
  try {
    renderer_->render(scene ? *scene : empty, c, style_);
    drawn_ = now;
  } catch (const std::exception& e) {
    report(std::string("viewport: ") + e.what(), true);
  }
  context_.makeCurrent();
}

render::Image EditorApp::viewportImage(int width, int height) {
  const int w = viewportWidth_, h = viewportHeight_;
  viewport_->resize(width, height);
  const render::RenderScene* scene = session_.viewport().scene();
  const render::RenderScene empty;
  render::Image image = renderer_->renderImage(scene ? *scene : empty, session_.camera(), style_);
  viewport_->resize(w, h);
  drawn_ = ViewportState();  // the texture now holds the screenshot's picture
  context_.makeCurrent();
  return image;
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

void EditorApp::drawTimeline(float left, float top, float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(left, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  ImGui::Begin("Timeline", nullptr, kFixedWindow);
  SimulationCache& cache = session_.cache();
  const EditorDocument& doc = session_.document();
  const int sceneSteps = doc.valid() ? doc.scene()->time.steps : 0;

  ImGui::BeginDisabled(!doc.valid() || cache.running());
  if (ImGui::Button("Simulate")) {
    const std::string error = session_.timeline().simulate();
    report(error.empty() ? "simulating " + std::to_string(sceneSteps) + " steps" : error,
           !error.empty());
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Text("%d steps (time.steps)", sceneSteps);
  ImGui::SameLine();
  ImGui::BeginDisabled(!cache.running());
  if (ImGui::Button("Cancel")) cache.cancel();
  ImGui::EndDisabled();
  ImGui::SameLine();
  const int available = cache.frameCount();
  char progress[96];
  std::snprintf(progress, sizeof progress, "%d / %d states (%s)", available,
                cache.requestedFrames(), SimulationCache::statusName(cache.status()));
  ImGui::ProgressBar(float(cache.progress()), ImVec2(-1, 0), progress);

  if (cache.status() == SimulationCache::Status::Failed) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("simulation failed: %s", cache.error().c_str());
    ImGui::PopStyleColor();
  } else if (session_.timeline().cacheStale()) {
    ImGui::TextColored(
        kWarningColour,
        "The scene changed since this simulation: the frames are stale. Simulate again.");
  }

  Playback& playback = session_.playback();
  // The timeline spans the scene's steps even before they are simulated (keys can be set
  // anywhere); beyond the cache the viewport keeps the last cached state.
  const int frames = session_.timeline().frames();
  ImGui::BeginDisabled(frames <= 1);
  if (ImGui::Button("|<")) playback.step(-1, frames);
  ImGui::SameLine();
  ImGui::BeginDisabled(available == 0);
  if (ImGui::Button(playback.playing() ? "Pause" : "Play")) togglePlayback();
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button(">|")) playback.step(1, frames);
  ImGui::SameLine();
  int k = playback.frame();
  ImGui::SetNextItemWidth(std::max(100.0f, ImGui::GetContentRegionAvail().x - 260.0f));
  if (ImGui::SliderInt("##frame", &k, 0, std::max(frames - 1, 0),
                       k < available ? "state %d" : "state %d (not simulated)"))
    playback.scrub(k, frames);
  drawKeyTicks(frames);
  ImGui::EndDisabled();
  ImGui::SameLine();
  const auto scene = cache.scene();
  const auto f = cache.frame(playback.frame());
  if (f && scene) {
    ImGui::Text("t = %.4f s", f->state * scene->time.dt);
    ImGui::Text("contacts: take-off %d, stick %d, slip %d   PD iterations %d, residual %.3g m/s^2",
                f->stats.takeoff, f->stats.stick, f->stats.slip, f->stats.pdIterations,
                f->stats.residual);
  } else {
    ImGui::Text("t = %.4f s", session_.timeline().time());
    ImGui::TextDisabled(available == 0
                            ? "no frames: press Simulate"
                            : "not simulated this far: the view shows the last cached state");
  }
  if (session_.placement().activeObject().kind == EditorObject::Kind::Handle)
    keyControls();
  else
    ImGui::TextDisabled("Space: play/pause   Left/Right: step one state");
  ImGui::End();
}

void EditorApp::drawKeyTicks(int frames) {
  // The active handle's keys as ticks on the slider just drawn, where its grab would stand at
  // the key's frame (Dear ImGui 1.86 SliderBehaviorT: 2 px padding, a grab of
  // max(width / (range + 1), GrabMinSize) whose centre travels the rest).
  const std::vector<HandleKey> keys = session_.placement().keys();
  const EditorDocument& doc = session_.document();
  if (keys.empty() || frames <= 1 || !doc.valid()) return;
  const double dt = doc.scene()->time.dt;
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  const float padding = 2.0f, width = high.x - low.x - 2.0f * padding;
  const float grab =
      std::min(std::max(width / float(frames), ImGui::GetStyle().GrabMinSize), width);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (const HandleKey& key : keys) {
    const double frame = key.time / dt;
    if (frame < -0.5 || frame > frames - 0.5) continue;
    const float x =
        low.x + padding + 0.5f * grab + float(frame / double(frames - 1)) * (width - grab);
    draw->AddTriangleFilled(ImVec2(x, high.y - 6.0f), ImVec2(x - 4.0f, high.y + 1.0f),
                            ImVec2(x + 4.0f, high.y + 1.0f), IM_COL32(255, 200, 40, 255));
    draw->AddLine(ImVec2(x, low.y), ImVec2(x, high.y), IM_COL32(255, 200, 40, 160), 1.0f);
  }
}

void EditorApp::keyControls() {
  // The active handle at the playback frame: its offset (dragged with the gizmo or typed here),
  // and its keys.
  const auto offset = session_.placement().handleOffset();
  ImGui::AlignTextToFramePadding();
  ImGui::Text("%s", session_.placement().activeObject().path().c_str());
  ImGui::SameLine();
  double v[3] = {0, 0, 0};
  if (offset) v[0] = offset->x(), v[1] = offset->y(), v[2] = offset->z();
  ImGui::SetNextItemWidth(230.0f);
  // "###": one widget identity whatever the label says, so typing is not cut off when the first
  // keystroke makes the offset pending.
  if (ImGui::InputScalarN(session_.placement().handleOffsetPending()
                              ? "offset (m, not keyed)###offset"
                              : "offset (m)###offset",
                          ImGuiDataType_Double, v, 3, nullptr, nullptr, "%.4g")) {
    const std::string error = session_.placement().setHandleOffset(Vec3(v[0], v[1], v[2]));
    if (!error.empty()) report(error, true);
  }
  auto action = [&](const char* label, const std::function<std::string()>& run, const char* done) {
    ImGui::SameLine();
    if (ImGui::SmallButton(label)) {
      const std::string error = run();
      report(error.empty() ? done : error, !error.empty());
    }
  };
  action(
      "Set key (K)", [&] { return session_.placement().setKey(); }, "key set");
  action(
      "Delete key", [&] { return session_.placement().deleteKey(); }, "key deleted");
  action(
      "< key", [&] { return session_.placement().jumpToKey(-1); }, "previous key");
  action(
      "key >", [&] { return session_.placement().jumpToKey(1); }, "next key");
}

void EditorApp::drawFileDialog() {
  if (fileDialog_ == FileDialog::None) return;
  const char* title = fileDialog_ == FileDialog::Open ? "Open scene" : "Save scene as";
  if (!ImGui::IsPopupOpen(title)) {
    const std::string current = session_.document().file();
    std::snprintf(pathBuffer_, sizeof pathBuffer_, "%s", current.c_str());
    ImGui::OpenPopup(title);
  }
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("Scene file path (absolute, or relative to the working directory):");
    ImGui::SetNextItemWidth(520.0f);
    // The path is what the dialog is for: typing goes into it at once, without a click first.
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    const bool enter = ImGui::InputText("##path", pathBuffer_, sizeof pathBuffer_,
                                        ImGuiInputTextFlags_EnterReturnsTrue);
    const bool ok = ImGui::Button(fileDialog_ == FileDialog::Open ? "Open" : "Save") || enter;
    ImGui::SameLine();
    const bool cancel = ImGui::Button("Cancel");
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
      carryOut(action, pendingFile_);
    }
    ImGui::EndPopup();
  }
}

}  // namespace weft::editor
