#include "InspectorPanel.h"

#include "EditorSession.h"

#include <weft/render/ColorMap.h>

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <string>

namespace weft::editor {
namespace {

// The viewport's branch colours, for the text.
ImVec4 branchColour(ContactBranch branch) {
  if (branch == ContactBranch::None) return ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled);
  const render::Rgb c = render::branchColor(static_cast<render::ContactBranch>(branch));
  return ImVec4(c.x(), c.y(), c.z(), 1.0f);
}

void vectorText(const char* label, const Vec3& v, const char* unit) {
  ImGui::Text("%-9s % .5f % .5f % .5f %s  |%.4g|", label, v.x(), v.y(), v.z(), unit, v.norm());
}

// One series as a line plot, with the state shown in the viewport marked by a vertical line.
// Series index k is the step that produced state k + 1.
void plot(const char* label, const std::vector<float>& values, int state, const char* overlay) {
  const float width = ImGui::GetContentRegionAvail().x;
  ImGui::PlotLines(label, values.empty() ? nullptr : values.data(), int(values.size()), 0, overlay,
                   FLT_MAX, FLT_MAX, ImVec2(width, 44.0f));
  if (values.size() < 2 || state < 1) return;
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  const ImGuiStyle& style = ImGui::GetStyle();
  const float left = low.x + style.FramePadding.x, right = high.x - style.FramePadding.x;
  const float t = float(std::min<std::size_t>(std::size_t(state - 1), values.size() - 1)) /
                  float(values.size() - 1);
  const float x = left + t * (right - left);
  ImGui::GetWindowDrawList()->AddLine(ImVec2(x, low.y), ImVec2(x, high.y),
                                      IM_COL32(255, 210, 60, 200), 1.5f);
}

}  // namespace

void InspectorPanel::draw(EditorSession& session) {
  ImGui::Checkbox("Branch colours", &session.viewport().contactColours);
  ImGui::SameLine();
  ImGui::Checkbox("Force arrows", &session.viewport().forceArrows);
  ImGui::TextDisabled("Overlays on cached states of contact scenes.");
  ImGui::Separator();

  // The vertex inspector.
  const int focus = session.selection().focus();
  if (focus < 0) {
    ImGui::TextDisabled("Click a cloth vertex to inspect it.");
  } else if (const auto r = session.inspect()) {
    ImGui::Text("Vertex %d (cloth %d, vertex %d), state %d", r->node, r->cloth, r->localVertex,
                r->state);
    vectorText("position", r->position, "m");
    vectorText("velocity", r->velocity, "m/s");
    ImGui::TextUnformatted("branch   ");
    ImGui::SameLine(0, 0);
    ImGui::TextColored(branchColour(r->branch), "%s",
                       r->branch == ContactBranch::None ? "no contact" : branchName(r->branch));
    // The task loss's gradient at this vertex and state: dL/dx_n with the state's velocities held
    // (the loss's units per metre), from a backward pass over the cached run.
    if (const auto g = session.gradients().at(r->node, r->state)) {
      vectorText("dL/dx", *g, "/m");
      gradientError_.clear();
    } else if (session.gradients().computing()) {
      ImGui::TextDisabled("computing the loss gradient (backward pass)...");
    } else if (ImGui::SmallButton("Compute loss gradient")) {
      gradientError_ = session.gradients().compute();
    }
    const std::string& error =
        gradientError_.empty() ? session.gradients().error() : gradientError_;
    if (!error.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.30f, 1.0f));
      ImGui::TextWrapped("%s", error.c_str());
      ImGui::PopStyleColor();
    }
    if (!r->contacts.empty()) {
      vectorText("force", r->contactForce, "N");
      vectorText("impulse", r->contactImpulse, "N s");
      if (ImGui::BeginTable("contacts", 4,
                            ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("with");
        ImGui::TableSetupColumn("branch");
        ImGui::TableSetupColumn("|force| (N)");
        ImGui::TableSetupColumn("normal");
        ImGui::TableHeadersRow();
        for (const VertexContact& c : r->contacts) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          if (c.obstacle >= 0)
            ImGui::Text("obstacle %d", c.obstacle);
          else
            ImGui::Text("vertex %d", c.partner);
          ImGui::TableNextColumn();
          ImGui::TextColored(branchColour(c.branch), "%s", branchName(c.branch));
          ImGui::TableNextColumn();
          ImGui::Text("%.4g", c.force.norm());
          ImGui::TableNextColumn();
          ImGui::Text("%.2f %.2f %.2f", c.normal.x(), c.normal.y(), c.normal.z());
        }
        ImGui::EndTable();
      }
    } else {
      ImGui::TextDisabled("No contact in the step that produced this state.");
    }
  } else {
    ImGui::Text("Vertex %d", focus);
    ImGui::TextDisabled("Simulate to inspect its motion and contacts.");
  }
  ImGui::Separator();

  // Per-step plots from the cached StepStats.
  const StepStatsSeries& series = session.stepSeries();
  if (series.size() == 0) {
    ImGui::TextDisabled("Per-step plots appear as the simulation runs.");
    return;
  }
  const int state = session.playback().frame();
  const auto frame = session.cache().frame(state);
  char text[96];
  if (series.anyContact()) {
    const StepStats* s = frame ? &frame->stats : nullptr;
    std::snprintf(text, sizeof text, "take-off %d", s ? s->takeoff : 0);
    plot("##takeoff", series.takeoff(), state, text);
    std::snprintf(text, sizeof text, "stick %d", s ? s->stick : 0);
    plot("##stick", series.stick(), state, text);
    std::snprintf(text, sizeof text, "slip %d", s ? s->slip : 0);
    plot("##slip", series.slip(), state, text);
  } else {
    ImGui::TextDisabled("No contacts in this run.");
  }
  std::snprintf(text, sizeof text, "PD iterations %d", frame ? frame->stats.pdIterations : 0);
  plot("##pd", series.pdIterations(), state, text);
  std::snprintf(text, sizeof text, "log10 residual (m/s^2) %.3g",
                frame ? frame->stats.residual : 0.0);
  plot("##residual", series.log10Residual(), state, text);
}

}  // namespace weft::editor
