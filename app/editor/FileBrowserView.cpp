#include "FileBrowserView.h"

#include "EditorApp.h"

#include <imgui.h>

#include <filesystem>

namespace weft::editor {

FileBrowserEvent drawFileBrowser(FileBrowser& browser, const std::vector<std::string>& places,
                                 const std::string& picked, EditorApp& app, float width,
                                 float height) {
  FileBrowserEvent event;
  ImGui::PushID("file-browser");
  if (ImGui::Button("Up") && browser.up())
    event = {FileBrowserEvent::Kind::Moved, browser.folder().string()};
  app.noteLastItem("browser:up");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(width - ImGui::GetItemRectSize().x - ImGui::GetStyle().ItemSpacing.x);
  const std::string folder = browser.folder().string();
  if (ImGui::BeginCombo("##places", folder.c_str(), ImGuiComboFlags_HeightLarge)) {
    for (std::size_t k = 0; k < places.size(); ++k) {
      ImGui::PushID(static_cast<int>(k));
      if (ImGui::Selectable(places[k].c_str(), places[k] == folder) && browser.show(places[k]))
        event = {FileBrowserEvent::Kind::Moved, browser.folder().string()};
      app.noteLastItem("browser:place:" + std::to_string(k));
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  app.noteLastItem("browser:places");
  if (!browser.error().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.30f, 1.0f));
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    ImGui::TextWrapped("%s", browser.error().c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
  }

  // The entries; acted on after the list is drawn, since opening a folder replaces them.
  const std::vector<FileEntry>& entries = browser.entries();
  const std::string pickedName = std::filesystem::path(picked).filename().string();
  const bool pickedHere =
      std::filesystem::path(picked).lexically_normal().parent_path() == browser.folder();
  int clicked = -1;
  bool doubleClicked = false;
  ImGui::BeginChild("##entries", ImVec2(width, height), true);
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(entries.size()));
  while (clipper.Step())
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const FileEntry& e = entries[static_cast<std::size_t>(i)];
      const std::string label = e.folder ? e.name + "/" : e.name;
      const bool selected = !e.folder && pickedHere && e.name == pickedName;
      ImGui::PushID(i);
      if (ImGui::Selectable(
              label.c_str(), selected,
              ImGuiSelectableFlags_AllowDoubleClick | ImGuiSelectableFlags_DontClosePopups)) {
        clicked = i;
        doubleClicked = ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
      }
      app.noteLastItem("browser:entry:" + e.name);
      ImGui::PopID();
    }
  if (entries.empty()) ImGui::TextDisabled("(no folders or files of this kind here)");
  ImGui::EndChild();
  ImGui::PopID();

  if (clicked >= 0) {
    const FileEntry entry = entries[static_cast<std::size_t>(clicked)];
    if (entry.folder) {
      if (browser.enter(entry)) event = {FileBrowserEvent::Kind::Moved, browser.folder().string()};
    } else {
      const bool confirmed = doubleClicked && browser.picked() == browser.pathOf(entry);
      browser.pick(entry);
      event = {confirmed ? FileBrowserEvent::Kind::Confirmed : FileBrowserEvent::Kind::Picked,
               browser.pathOf(entry)};
    }
  }
  return event;
}

}  // namespace weft::editor
