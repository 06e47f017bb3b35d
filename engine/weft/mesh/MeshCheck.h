#pragma once
// Mesh sanity checks run on every cloth before it is simulated: a degenerate triangle would
// make the stretch projection divide by zero, an unreferenced vertex would have zero mass.

#include <weft/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace weft {

struct MeshReport {
  std::vector<int> nonFiniteVertices;    // coordinates that are NaN or infinite
  std::vector<int> badIndexTriangles;    // an index out of range or repeated
  std::vector<int> degenerateTriangles;  // zero or near-zero area relative to its edges
  std::vector<int> unreferencedVertices;
  std::vector<std::pair<int, int>> nonManifoldEdges;  // edges shared by more than two triangles
  std::vector<int> thinTriangles;  // smallest angle under 5 degrees (a warning only)

  bool hasErrors() const {
    return !nonFiniteVertices.empty() || !badIndexTriangles.empty() ||
           !degenerateTriangles.empty() || !unreferencedVertices.empty();
  }
};

MeshReport checkMesh(const TriangleMesh& mesh);

// Drops the triangles listed (e.g. the degenerate ones); vertex order and count are kept.
void removeTriangles(TriangleMesh& mesh, const std::vector<int>& triangles);

// "3 (12, 40, 41)" style list of at most `limit` indices, for messages.
std::string formatIndexList(const std::vector<int>& indices, std::size_t limit = 10);

}  // namespace weft
