#include "TargetPanel.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <imgui.h>

#include <cfloat>
#include <cstdio>
#include <string>

namespace weft::editor {

void TargetPanel::draw(EditorSession& session, EditorApp& app) {
  EditorDocument& doc = session.document();

  // The loss of the cached run under the task as it is now.
  const LossValue& loss = session.targets().liveLoss();
  if (loss.available) {
    ImGui::Text("Loss of the cached run: %.6g", loss.total);
    for (const auto& [name, value] : loss.terms) ImGui::BulletText("%s: %.6g", name.c_str(), value);
  } else {
    ImGui::TextDisabled("Loss: %s", loss.note.c_str());
  }
  ImGui::Separator();

  // Final-frame targets.
  const std::vector<FinalTarget> list = session.targets().all();
  const std::vector<int>& selected = session.selection().nodes();
  ImGui::Text("Final-frame targets: %zu", list.size());
  ImGui::BeginDisabled(selected.empty());
  if (ImGui::Button("Set at selected vertices")) {
    const std::string error = session.targets().setTargetsFromSelection();
    app.report(
        error.empty() ? "targets set at " + std::to_string(selected.size()) + " vertices" : error,
        !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Remove selected")) {
    const std::string error = session.targets().removeTargets(selected);
    if (!error.empty()) app.report(error, true);
  }
  ImGui::EndDisabled();
  ImGui::BeginDisabled(list.empty());
  if (ImGui::Button("Clear all targets")) {
    const std::string error = session.targets().removeTargets({});
    if (!error.empty()) app.report(error, true);
  }
  ImGui::EndDisabled();
  ImGui::TextDisabled("Targets start at the vertices' shown positions:");
  ImGui::TextDisabled("scrub to the last state first. Alt + drag in the");
  ImGui::TextDisabled("viewport moves the selected targets.");

  if (!list.empty()) {
    if (doc.find("task.loss.final")) {
      const nlohmann::json* w = doc.find("task.loss.final.weight");
      double weight = w && w->is_number() ? w->get<double>() : 1.0;
      if (ImGui::InputDouble("weight", &weight, 0.0, 0.0, "%.6g",
                             ImGuiInputTextFlags_EnterReturnsTrue)) {
        const std::string error = doc.setValue("task.loss.final.weight", weight);
        if (!error.empty()) app.report(error, true);
      }
    }
    ImGui::InputScalarN("offset (m)", ImGuiDataType_Double, offset_, 3, nullptr, nullptr, "%.4g");
    ImGui::BeginDisabled(selected.empty());
    if (ImGui::Button("Move selected targets by the offset")) {
      const std::string error =
          session.targets().moveTargets(selected, Vec3(offset_[0], offset_[1], offset_[2]));
      if (!error.empty()) app.report(error, true);
    }
    ImGui::EndDisabled();
    // One row per target (the first 64: more are edited by selection and offset).
    if (ImGui::BeginChild("target-list",
                          ImVec2(0, std::min(220.0f, 26.0f * float(list.size()) + 8.0f)), true)) {
      for (std::size_t i = 0; i < list.size() && i < 64; ++i) {
        const FinalTarget& t = list[i];
        ImGui::PushID(t.node);
        double p[3] = {t.position.x(), t.position.y(), t.position.z()};
        char label[32];
        std::snprintf(label, sizeof label, "vertex %d", t.node);
        ImGui::SetNextItemWidth(210.0f);
        const bool changed =
            ImGui::InputScalarN(label, ImGuiDataType_Double, p, 3, nullptr, nullptr, "%.4f");
        if (ImGui::IsItemActivated()) ++editSerial_;
        if (changed) {
          const std::string error = session.targets().setTarget(
              t.node, Vec3(p[0], p[1], p[2]), "target field " + std::to_string(editSerial_));
          if (!error.empty()) app.report(error, true);
        }
        ImGui::SameLine();
        if (ImGui::SmallButton("x")) session.targets().removeTargets({t.node});
        ImGui::PopID();
      }
      if (list.size() > 64) ImGui::TextDisabled("... and %zu more", list.size() - 64);
    }
    ImGui::EndChild();
    const nlohmann::json* file = doc.find("task.loss.final.target");
    ImGui::TextDisabled("Written on save to %s",
                        file && file->is_string() ? file->get<std::string>().c_str() : "?");
  }
  ImGui::Separator();

  // A recorded motion as the trajectory term.
  const nlohmann::json* motion = doc.find("task.loss.trajectory.target");
  if (motion && motion->is_string()) {
    ImGui::TextWrapped("Target motion: %s", motion->get<std::string>().c_str());
    if (ImGui::Button("Remove target motion")) {
      const std::string error = session.targets().removeTargetMotion();
      if (!error.empty()) app.report(error, true);
    }
  } else {
    ImGui::TextDisabled("No target motion (a positions.npy of weft simulate).");
  }
  // The path on a line of its own, the buttons under it: side by side they did not fit the panel
  // ("Load shape" was clipped to "Lo").
  ImGui::SetNextItemWidth(-FLT_MIN);
  ImGui::InputText("##motion", motionPath_, sizeof motionPath_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A positions.npy for Load motion, or a mesh file for Load shape");
  ImGui::BeginDisabled(motionPath_[0] == '\0');
  if (ImGui::Button("Load motion")) {
    const std::string error = session.targets().loadTargetMotion(motionPath_);
    app.report(error.empty() ? std::string("target motion ") + motionPath_ : error, !error.empty());
  }
  ImGui::SameLine();
  // The final shape: a mesh of the garment's vertices, placed as the garment's own file.
  if (ImGui::Button("Load shape")) {
    const std::string error = session.targets().loadTargetMesh(motionPath_);
    app.report(error.empty() ? std::string("target shape ") + motionPath_ : error, !error.empty());
  }
  ImGui::EndDisabled();
  ImGui::Separator();

  // The built-in hemline term (the Dress task's loss).
  const nlohmann::json* hemline = doc.find("task.loss.hemline");
  if (hemline && hemline->is_object()) {
    const std::size_t count = hemline->contains("vertices") ? hemline->at("vertices").size() : 0;
    ImGui::TextWrapped(
        "Hemline: %zu vertices at %s m", count,
        hemline->contains("height") ? hemline->at("height").dump().c_str() : "(a cone's height)");
    if (ImGui::Button("Remove hemline")) {
      const std::string error = session.targets().removeHemline();
      if (!error.empty()) app.report(error, true);
    }
  } else {
    ImGui::TextDisabled("No hemline term.");
  }
  ImGui::SetNextItemWidth(120.0f);
  ImGui::InputDouble("height (m)##hemline", &hemlineHeight_, 0.0, 0.0, "%.4g");
  ImGui::SameLine();
  ImGui::BeginDisabled(selected.empty());
  if (ImGui::Button("Hemline at selected")) {
    const std::string error = session.targets().setHemline(hemlineHeight_);
    app.report(error.empty() ? "hemline set" : error, !error.empty());
  }
  ImGui::EndDisabled();
}

}  // namespace weft::editor
