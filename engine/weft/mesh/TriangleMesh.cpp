#include <weft/mesh/TriangleMesh.h>

#include <algorithm>
#include <array>

namespace weft {

double TriangleMesh::triangleArea(int t) const {
  const Vec3 a = vertices.row(triangles(t, 0));
  const Vec3 b = vertices.row(triangles(t, 1));
  const Vec3 c = vertices.row(triangles(t, 2));
  return 0.5 * (b - a).cross(c - a).norm();
}

Eigen::VectorXd TriangleMesh::lumpedAreas() const {
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(vertexCount());
  for (int t = 0; t < triangleCount(); ++t) {
    const double third = triangleArea(t) / 3.0;
    for (int k = 0; k < 3; ++k) areas[triangles(t, k)] += third;
  }
  return areas;
}

double TriangleMesh::totalArea() const {
  return areaAt(vertices);
}

double TriangleMesh::areaAt(const NodeMatrix& positions) const {
  double sum = 0.0;
  for (int t = 0; t < triangleCount(); ++t) {
    const Vec3 a = positions.row(triangles(t, 0));
    const Vec3 b = positions.row(triangles(t, 1));
    const Vec3 c = positions.row(triangles(t, 2));
    sum += 0.5 * (b - a).cross(c - a).norm();
  }
  return sum;
}

void TriangleMesh::append(const TriangleMesh& other) {
  const int offset = vertexCount();
  NodeMatrix v(vertices.rows() + other.vertices.rows(), 3);
  v << vertices, other.vertices;
  TriangleIndices f(triangles.rows() + other.triangles.rows(), 3);
  f << triangles, (other.triangles.array() + offset).matrix();
  vertices = std::move(v);
  triangles = std::move(f);
}

std::vector<MeshEdge> buildEdges(const TriangleMesh& mesh) {
  std::vector<std::array<int, 3>> halfEdges;  // (a, b, face) with a < b
  halfEdges.reserve(3 * mesh.triangleCount());
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) {
      int a = mesh.triangles(t, k), b = mesh.triangles(t, (k + 1) % 3);
      if (a > b) std::swap(a, b);
      halfEdges.push_back({a, b, t});
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end());
  std::vector<MeshEdge> edges;
  for (const auto& h : halfEdges) {
    if (edges.empty() || edges.back().a != h[0] || edges.back().b != h[1])
      edges.push_back(MeshEdge{h[0], h[1], {}});
    edges.back().faces.push_back(h[2]);
  }
  return edges;
}

}  // namespace weft
