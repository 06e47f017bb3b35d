#pragma once
// What the editor's panels share in look: the fixed windows of the layout, and the colours of
// errors, warnings and a valid scene.

#include <imgui.h>

namespace weft::editor {

constexpr ImGuiWindowFlags kFixedWindow = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                          ImGuiWindowFlags_NoCollapse |
                                          ImGuiWindowFlags_NoBringToFrontOnFocus;
const ImVec4 kErrorColour(0.95f, 0.35f, 0.30f, 1.0f);
const ImVec4 kWarningColour(0.95f, 0.75f, 0.25f, 1.0f);
const ImVec4 kOkColour(0.45f, 0.85f, 0.45f, 1.0f);
// Steps that stopped at the iteration limit: the timeline's banner and ticks.
const ImVec4 kUnconvergedColour(0.80f, 0.12f, 0.12f, 1.0f);

}  // namespace weft::editor
