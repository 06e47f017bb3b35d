#include "MeshImportDialog.h"

#include "EditorApp.h"
#include "EditorSession.h"
#include "FileBrowserView.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace weft::editor {
namespace {

const char* title(MeshImportDialog::Kind kind) {
  return kind == MeshImportDialog::Kind::Garment ? "Import garment" : "Add mesh obstacle";
}

bool vector3(const char* label, Vec3& v) {
  double d[3] = {v.x(), v.y(), v.z()};
  const bool changed =
      ImGui::InputScalarN(label, ImGuiDataType_Double, d, 3, nullptr, nullptr, "%.4g");
  if (changed) v = Vec3(d[0], d[1], d[2]);
  return changed;
}

}  // namespace

void MeshImportDialog::open(Kind kind) {
  kind_ = kind;
  requested_ = true;
  previewed_ = false;
}

void MeshImportDialog::draw(EditorSession& session, EditorApp& app) {
  const char* name = title(kind_);
  if (requested_) {
    ImGui::OpenPopup(name);
    requested_ = false;
    // Browse from the file typed last, else the scene's folder, else the working directory.
    if (!browser_.showFolderOf(path_) && !browser_.showFolderOf(session.document().directory()))
      browser_.show(".");
  }
  visible_ = false;
  if (!ImGui::BeginPopupModal(name, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  visible_ = true;
  bool changed = false, checkNow = false;
  ImGui::TextUnformatted(
      kind_ == Kind::Garment
          ? "Mesh file (OBJ, glTF, FBX, PLY, ...; absolute or relative to the working directory):"
          : "Obstacle mesh file (a closed, outward-facing surface):");
  ImGui::SetNextItemWidth(520.0f);
  // The path is what the dialog is for: typing goes into it at once, and Enter imports (as the
  // Open and Save As dialogs do). Esc, once the field is let go, cancels.
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  bool enter =
      ImGui::InputText("##file", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue);
  changed |= ImGui::IsItemEdited();
  const FileBrowserEvent browsed =
      drawFileBrowser(browser_, browsePlaces(session.document().file(), session.recent().files()),
                      path_, app, 520.0f, 160.0f);
  if (browsed.kind == FileBrowserEvent::Kind::Picked ||
      browsed.kind == FileBrowserEvent::Kind::Confirmed) {
    std::snprintf(path_, sizeof path_, "%s", browsed.path.c_str());
    changed = true;
    checkNow = true;  // a picked file is checked at once, so its size and unit show
    enter |= browsed.kind == FileBrowserEvent::Kind::Confirmed;
  }
  ImGui::PushItemWidth(260.0f);
  changed |= ImGui::Checkbox("Fit to a size", &options_.fit);
  if (options_.fit) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    changed |= ImGui::InputDouble("largest extent (m)", &options_.fitSize, 0.0, 0.0, "%.4g");
    ImGui::TextDisabled("The mesh is scaled to that size and its centre moved to the translation.");
  } else {
    changed |= ImGui::InputDouble("scale (file units to m)", &options_.scale, 0.0, 0.0, "%.6g");
  }
  changed |= vector3("rotate (deg, X then Y then Z)", options_.rotateDeg);
  changed |= vector3("translate (m)", options_.translate);
  if (kind_ == Kind::Garment)
    changed |= ImGui::Checkbox("Drop degenerate triangles (mesh.repair)", &options_.repair);
  else
    changed |= ImGui::Checkbox("Smooth normals", &options_.smoothNormals);
  ImGui::PopItemWidth();
  if (changed) previewed_ = false;

  options_.file = path_;
  const auto check = [&] {
    preview_ = kind_ == Kind::Garment ? session.additions().previewGarment(options_)
                                      : prepareMeshObstacle(options_, session.document().file(),
                                                            session.document().directory());
    previewed_ = true;
  };
  if (ImGui::Button("Check") || checkNow) check();
  ImGui::SameLine();
  const bool import = ImGui::Button(kind_ == Kind::Garment ? "Import" : "Add") || enter;
  app.noteLastItem("dialog:confirm");
  ImGui::SameLine();
  const bool cancel =
      ImGui::Button("Cancel") || (!ImGui::IsAnyItemActive() && !ImGui::IsWindowAppearing() &&
                                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false));
  if (previewed_) {
    if (preview_.ok()) {
      const Vec3 size = preview_.upper - preview_.lower;
      ImGui::Text("%d vertices, %d triangles; %.3g x %.3g x %.3g m once placed", preview_.vertices,
                  preview_.triangles, size.x(), size.y(), size.z());
    } else {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.30f, 1.0f));
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 520.0f);
      ImGui::TextWrapped("%s", preview_.error.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopStyleColor();
    }
    for (const std::string& w : preview_.warnings) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.75f, 0.25f, 1.0f));
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 520.0f);
      ImGui::TextWrapped("warning: %s", w.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopStyleColor();
    }
    // The units that would give the mesh a plausible size: one click sets the scale.
    if (!preview_.units.empty()) {
      const double extent = (preview_.fileUpper - preview_.fileLower).maxCoeff();
      ImGui::TextUnformatted("The file is in:");
      const LengthUnit* chosen = nullptr;
      for (const LengthUnit& u : preview_.units) {
        ImGui::SameLine();
        char label[96];
        std::snprintf(label, sizeof label, "%s (%.3g m)", u.name.c_str(), extent * u.metres);
        if (ImGui::SmallButton(label)) chosen = &u;
        app.noteLastItem("units:" + u.name);
      }
      if (chosen) {
        options_.fit = false;
        options_.scale = chosen->metres;
        app.report("scale set to " + std::to_string(chosen->metres) + " (" + chosen->name + ")",
                   false);
        check();
      }
    }
  }
  if (import) {
    const std::string error = kind_ == Kind::Garment
                                  ? session.additions().importGarment(options_)
                                  : session.additions().importMeshObstacle(options_);
    if (error.empty()) {
      app.report(std::string(kind_ == Kind::Garment ? "imported " : "added mesh obstacle ") +
                     options_.file,
                 false);
      // The camera frames the scene with what was added (it may lie far from the old view).
      session.frameCamera(static_cast<float>(app.viewportWidth()) /
                          static_cast<float>(std::max(app.viewportHeight(), 1)));
      ImGui::CloseCurrentPopup();
    } else {
      // Kept open, showing why: the document is unchanged.
      preview_ = MeshImport();
      preview_.error = error;
      previewed_ = true;
      app.report(error, true);
    }
  }
  if (cancel) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace weft::editor
