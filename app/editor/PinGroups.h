#pragma once
// Pin groups: the scene's fixed attachments, each a group of held vertices with an optional name
// (attachments.J.name) and a marker colour (render::pinGroupColor, by the group's number among
// the scene's fixed attachments, cloths in order, as the viewport and `weft render` draw them).

#include <weft/scene/Scene.h>

#include <string>
#include <vector>

namespace weft::editor {

struct PinGroup {
  int cloth = 0;
  int attachment = 0;      // index in the cloth's attachments
  int group = 0;           // number among the scene's fixed attachments: the colour's index
  std::string name;        // "" when the attachment has none
  std::vector<int> nodes;  // global node indices (ClothNodes.h)
};

// Every fixed attachment of `scene` (a validated scene; its document holds the names).
std::vector<PinGroup> pinGroups(const Scene& scene);

}  // namespace weft::editor
