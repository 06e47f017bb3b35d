#include "DocumentFields.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <imgui.h>

namespace weft::editor {
namespace {

double numberAt(const EditorDocument& doc, const std::string& path, double fallback) {
  const nlohmann::json* v = doc.find(path);
  return v && v->is_number() ? v->get<double>() : fallback;
}

}  // namespace

void DocumentFields::apply(const std::string& error, unsigned itemId) {
  if (!error.empty()) app_.report(error, true);
  lastEditId_ = itemId;
}

template <class Value, class Widget>
bool DocumentFields::field(const char* label, const std::string& path, Value value,
                           Widget&& widget) {
  // One document edit per change; consecutive changes of the same item (typing, dragging) merge
  // into one undo step.
  ImGui::PushID(path.c_str());
  const ImGuiID id = ImGui::GetID(label);
  const bool changed = widget(&value);
  if (changed) {
    const bool coalesce = id == lastEditId_ && !ImGui::IsItemActivated();
    apply(session_.document().setValue(path, value, coalesce), id);
  }
  if (ImGui::IsItemDeactivated()) lastEditId_ = 0;
  ImGui::PopID();
  return changed;
}

bool DocumentFields::number(const char* label, const std::string& path, double fallback,
                            const char* format) {
  return field(label, path, numberAt(session_.document(), path, fallback),
               [&](double* v) { return ImGui::InputDouble(label, v, 0.0, 0.0, format); });
}

bool DocumentFields::integer(const char* label, const std::string& path, int fallback) {
  return field(label, path, static_cast<int>(numberAt(session_.document(), path, fallback)),
               [&](int* v) { return ImGui::InputInt(label, v); });
}

bool DocumentFields::vector(const char* label, const std::string& path, const double* fallback) {
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
    apply(session_.document().setValue(path, nlohmann::json::array({v[0], v[1], v[2]}), coalesce),
          id);
  }
  if (ImGui::IsItemDeactivated()) lastEditId_ = 0;
  ImGui::PopID();
  return changed;
}

void DocumentFields::combo(const char* label, const std::string& path, const char* const* options,
                           int count, const char* fallback) {
  const nlohmann::json* j = session_.document().find(path);
  const std::string current = j && j->is_string() ? j->get<std::string>() : fallback;
  ImGui::PushID(path.c_str());
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (int i = 0; i < count; ++i)
      if (ImGui::Selectable(options[i], current == options[i]) && current != options[i])
        apply(session_.document().setValue(path, options[i]));
    ImGui::EndCombo();
  }
  ImGui::PopID();
}

}  // namespace weft::editor
