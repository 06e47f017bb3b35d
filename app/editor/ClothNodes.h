#pragma once
// Global node numbers of the cloths: the engine's ClothModel numbers each cloth's vertices one
// after another (ClothModel::vertexOffset: entry c is cloth c's first node, the last entry the
// node count). The editor maps between global nodes and (cloth, local vertex) in the selection,
// handles, picking and the vertex inspector through these two functions.

#include <weft/scene/Scene.h>

#include <vector>

namespace weft::editor {

// The offsets ClothModel::vertexOffset holds for `scene`, without building the model.
std::vector<int> clothVertexOffsets(const Scene& scene);

// The cloth a global node belongs to, -1 when it is no cloth vertex.
int clothOfNode(const std::vector<int>& vertexOffset, int node);

}  // namespace weft::editor
