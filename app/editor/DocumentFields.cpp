#include "DocumentFields.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <imgui.h>

#include <cstdio>

namespace weft::editor {
namespace {

double numberAt(const EditorDocument& doc, const std::string& path, double fallback) {
  const nlohmann::json* v = doc.find(path);
  return v && v->is_number() ? v->get<double>() : fallback;
}

}  // namespace

void DocumentFields::noteItem(const std::string& path) {
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  app_.noteItem(path, low.x + 10.0f, 0.5f * (low.y + high.y));
}

void DocumentFields::apply(const std::string& error, const std::string& field) {
  if (!error.empty()) app_.report(error, true);
  lastEditField_ = field;
}

template <class Value, class Widget>
bool DocumentFields::field(const std::string& path, Value value, Widget&& widget) {
  // One document edit per change; consecutive changes of the same field (typing, dragging) merge
  // into one undo step. The field is known by its path, not by an ImGui id: ImGui::GetID (1.86)
  // marks the id it returns as alive, and called before InputInt it made the widget's group
  // believe its active text field was alive before the group began, so the group reported no
  // item and ImGui's MarkItemEdited asserted on the first keystroke (issue 39's crash).
  ImGui::PushID(path.c_str());
  const bool changed = widget(&value);
  noteItem(path);
  if (changed) {
    const bool coalesce = path == lastEditField_ && !ImGui::IsItemActivated();
    apply(session_.document().setValue(path, value, coalesce), path);
  }
  if (ImGui::IsItemDeactivated()) lastEditField_.clear();
  ImGui::PopID();
  return changed;
}

bool DocumentFields::number(const char* label, const std::string& path, double fallback,
                            const char* format) {
  return field(path, numberAt(session_.document(), path, fallback),
               [&](double* v) { return ImGui::InputDouble(label, v, 0.0, 0.0, format); });
}

bool DocumentFields::integer(const char* label, const std::string& path, int fallback) {
  return field(path, static_cast<int>(numberAt(session_.document(), path, fallback)),
               [&](int* v) { return ImGui::InputInt(label, v); });
}

bool DocumentFields::vector(const char* label, const std::string& path, const double* fallback) {
  double v[3] = {fallback[0], fallback[1], fallback[2]};
  const nlohmann::json* j = session_.document().find(path);
  if (j && j->is_array() && j->size() == 3)
    for (int i = 0; i < 3; ++i)
      if ((*j)[std::size_t(i)].is_number()) v[i] = (*j)[std::size_t(i)].get<double>();
  ImGui::PushID(path.c_str());
  const bool changed =
      ImGui::InputScalarN(label, ImGuiDataType_Double, v, 3, nullptr, nullptr, "%.4g");
  noteItem(path);
  if (changed) {
    const bool coalesce = path == lastEditField_ && !ImGui::IsItemActivated();
    apply(session_.document().setValue(path, nlohmann::json::array({v[0], v[1], v[2]}), coalesce),
          path);
  }
  if (ImGui::IsItemDeactivated()) lastEditField_.clear();
  ImGui::PopID();
  return changed;
}

bool DocumentFields::text(const char* label, const std::string& path, const char* hint) {
  const nlohmann::json* j = session_.document().find(path);
  return field(path, j && j->is_string() ? j->get<std::string>() : std::string(),
               [&](std::string* v) {
                 char buffer[128];
                 std::snprintf(buffer, sizeof buffer, "%s", v->c_str());
                 if (!ImGui::InputTextWithHint(label, hint, buffer, sizeof buffer)) return false;
                 *v = buffer;
                 return true;
               });
}

void DocumentFields::combo(const char* label, const std::string& path, const char* const* options,
                           int count, const char* fallback) {
  const nlohmann::json* j = session_.document().find(path);
  const std::string current = j && j->is_string() ? j->get<std::string>() : fallback;
  ImGui::PushID(path.c_str());
  const bool open = ImGui::BeginCombo(label, current.c_str());
  noteItem(path);
  if (open) {
    for (int i = 0; i < count; ++i)
      if (ImGui::Selectable(options[i], current == options[i]) && current != options[i])
        apply(session_.document().setValue(path, options[i]));
    ImGui::EndCombo();
  }
  ImGui::PopID();
}

}  // namespace weft::editor
