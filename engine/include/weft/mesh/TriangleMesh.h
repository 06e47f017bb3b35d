#pragma once
// A triangle mesh as Weft stores it: vertex positions and triangles, in file order.

#include <weft/core/Types.h>

#include <vector>

namespace weft {

struct TriangleMesh {
  NodeMatrix vertices;        // m x 3
  TriangleIndices triangles;  // t x 3, counter-clockwise seen from the front side

  int vertexCount() const { return static_cast<int>(vertices.rows()); }
  int triangleCount() const { return static_cast<int>(triangles.rows()); }

  double triangleArea(int t) const;
  // Lumped (one third of each incident triangle) area per vertex.
  Eigen::VectorXd lumpedAreas() const;
  double totalArea() const;
  // The total area of these triangles with their vertices at `positions` (m x 3, same order):
  // a deformed state's area (the Bowl's area ratio, DiffCloth Fig. 5, is it over totalArea()).
  double areaAt(const NodeMatrix& positions) const;
  void append(const TriangleMesh& other);  // concatenates, offsetting the other's indices
};

// An undirected edge with the (one or two, more if non-manifold) triangles that share it.
struct MeshEdge {
  int a, b;                // a < b
  std::vector<int> faces;  // triangles containing the edge
};

// Unique edges of the mesh, sorted by (a, b).
std::vector<MeshEdge> buildEdges(const TriangleMesh& mesh);

}  // namespace weft
