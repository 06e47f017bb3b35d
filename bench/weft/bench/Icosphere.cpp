#include "Icosphere.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace weft::bench {

TriangleMesh icosphere(const Vec3& center, double radius, int subdivisions) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    // Edge midpoints are shared between the two triangles of an edge, so the mesh stays welded.
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(4 * f.size());
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  // Outward orientation does not depend on remembering the table's winding: flip on a negative
  // enclosed volume (MeshShape signs distances by the triangles' orientation).
  double volume = 0.0;
  for (const auto& t : f) volume += v[t[0]].dot(v[t[1]].cross(v[t[2]]));
  if (volume < 0.0)
    for (auto& t : f) std::swap(t[1], t[2]);
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = center + radius * v[i];
  mesh.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) mesh.triangles(static_cast<Eigen::Index>(i), k) = f[i][k];
  return mesh;
}

}  // namespace weft::bench
