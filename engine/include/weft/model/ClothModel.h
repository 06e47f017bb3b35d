#pragma once
// All cloth pieces of a scene as one nodal system: node i of cloth c is global node
// offset[c] + i, in scene order (the order of every output).

#include <weft/core/Types.h>
#include <weft/mesh/TriangleMesh.h>
#include <weft/scene/Scene.h>

#include <vector>

namespace weft {

struct ClothModel {
  TriangleMesh rest;                // all cloths, concatenated
  std::vector<int> vertexOffset;    // first global node of each cloth (size = cloths + 1)
  std::vector<int> triangleOffset;  // first triangle of each cloth (size = cloths + 1)
  Eigen::VectorXd lumpedArea;       // m^2 per node
  Eigen::VectorXd mass;  // kg per node: density * lumped area (DiffCloth Sec. 3.1 lumped M)

  int nodeCount() const { return rest.vertexCount(); }
  int clothOf(int node) const;
};

ClothModel buildClothModel(const Scene& scene);

}  // namespace weft
