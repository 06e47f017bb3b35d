#include "ClothNodes.h"

#include <algorithm>

namespace weft::editor {

std::vector<int> clothVertexOffsets(const Scene& scene) {
  std::vector<int> offsets{0};
  for (const Cloth& c : scene.cloths) offsets.push_back(offsets.back() + c.mesh.vertexCount());
  return offsets;
}

int clothOfNode(const std::vector<int>& vertexOffset, int node) {
  if (vertexOffset.empty() || node < 0 || node >= vertexOffset.back()) return -1;
  return int(std::upper_bound(vertexOffset.begin(), vertexOffset.end(), node) -
             vertexOffset.begin()) -
         1;
}

}  // namespace weft::editor
