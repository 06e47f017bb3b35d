#include <weft/model/ClothModel.h>

#include <algorithm>

namespace weft {

int ClothModel::clothOf(int node) const {
  const auto it = std::upper_bound(vertexOffset.begin(), vertexOffset.end(), node);
  return static_cast<int>(it - vertexOffset.begin()) - 1;
}

ClothModel buildClothModel(const Scene& scene) {
  ClothModel model;
  model.rest.vertices.resize(0, 3);
  model.rest.triangles.resize(0, 3);
  model.vertexOffset.push_back(0);
  model.triangleOffset.push_back(0);
  for (const Cloth& c : scene.cloths) {
    model.rest.append(c.mesh);
    model.vertexOffset.push_back(model.rest.vertexCount());
    model.triangleOffset.push_back(model.rest.triangleCount());
  }
  model.lumpedArea = model.rest.lumpedAreas();
  model.mass.resize(model.nodeCount());
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (int i = model.vertexOffset[c]; i < model.vertexOffset[c + 1]; ++i)
      model.mass[i] = scene.cloths[c].material.density * model.lumpedArea[i];
  return model;
}

}  // namespace weft
