#include <weft/mesh/MeshCheck.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace weft {

MeshReport checkMesh(const TriangleMesh& mesh) {
  MeshReport report;
  const int m = mesh.vertexCount();
  for (int i = 0; i < m; ++i)
    if (!mesh.vertices.row(i).allFinite()) report.nonFiniteVertices.push_back(i);

  std::vector<char> referenced(m, 0);
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const int a = mesh.triangles(t, 0), b = mesh.triangles(t, 1), c = mesh.triangles(t, 2);
    if (a < 0 || b < 0 || c < 0 || a >= m || b >= m || c >= m || a == b || b == c || a == c) {
      report.badIndexTriangles.push_back(t);
      continue;
    }
    referenced[a] = referenced[b] = referenced[c] = 1;
    const Vec3 pa = mesh.vertices.row(a), pb = mesh.vertices.row(b), pc = mesh.vertices.row(c);
    const double l0 = (pb - pa).squaredNorm(), l1 = (pc - pb).squaredNorm(),
                 l2 = (pa - pc).squaredNorm();
    const double longest = std::max({l0, l1, l2});
    const double area2 = (pb - pa).cross(pc - pa).norm();  // twice the area
    // Relative test: area against the square of the longest edge, so units do not matter.
    if (!(longest > 0.0) || area2 <= 1e-10 * longest) {
      report.degenerateTriangles.push_back(t);
      continue;
    }
    // Smallest angle (opposite the shortest edge): sin = 2 area / (product of the other two).
    double sq[3] = {l0, l1, l2};
    std::sort(sq, sq + 3);
    const double sinMin = area2 / std::sqrt(sq[1] * sq[2]);
    if (sinMin < std::sin(5.0 * M_PI / 180.0)) report.thinTriangles.push_back(t);
  }
  if (mesh.triangleCount() > 0 || m > 0)
    for (int i = 0; i < m; ++i)
      if (!referenced[i]) report.unreferencedVertices.push_back(i);

  if (report.badIndexTriangles.empty()) {
    for (const MeshEdge& e : buildEdges(mesh))
      if (e.faces.size() > 2) report.nonManifoldEdges.emplace_back(e.a, e.b);
  }
  return report;
}

void removeTriangles(TriangleMesh& mesh, const std::vector<int>& triangles) {
  std::vector<char> drop(mesh.triangleCount(), 0);
  for (int t : triangles) drop[t] = 1;
  TriangleIndices kept(mesh.triangleCount() - static_cast<int>(triangles.size()), 3);
  int k = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t)
    if (!drop[t]) kept.row(k++) = mesh.triangles.row(t);
  mesh.triangles = kept.topRows(k);
}

std::string formatIndexList(const std::vector<int>& indices, std::size_t limit) {
  std::ostringstream s;
  s << indices.size() << " (";
  for (std::size_t i = 0; i < indices.size() && i < limit; ++i) s << (i ? ", " : "") << indices[i];
  if (indices.size() > limit) s << ", ...";
  s << ")";
  return s.str();
}

}  // namespace weft
