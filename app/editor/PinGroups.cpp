#include "PinGroups.h"

#include "ClothNodes.h"

namespace weft::editor {

std::vector<PinGroup> pinGroups(const Scene& scene) {
  const std::vector<int> offsets = clothVertexOffsets(scene);
  const nlohmann::json* cloths =
      scene.document.contains("cloths") ? &scene.document["cloths"] : nullptr;
  std::vector<PinGroup> groups;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const auto& attachments = scene.cloths[c].attachments;
    for (std::size_t a = 0; a < attachments.size(); ++a) {
      if (attachments[a].kind != Attachment::Kind::Fixed) continue;
      PinGroup g;
      g.cloth = static_cast<int>(c);
      g.attachment = static_cast<int>(a);
      g.group = static_cast<int>(groups.size());
      if (cloths && c < cloths->size()) {
        const nlohmann::json& at = (*cloths)[c].value("attachments", nlohmann::json::array());
        if (a < at.size() && at[a].contains("name") && at[a]["name"].is_string())
          g.name = at[a]["name"].get<std::string>();
      }
      for (int v : attachments[a].vertices) g.nodes.push_back(offsets[c] + v);
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

}  // namespace weft::editor
