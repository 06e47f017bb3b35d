#include <weft/mesh/BoundaryLoops.h>

#include <algorithm>
#include <numeric>

namespace weft {
namespace {

int findRoot(std::vector<int>& parent, int v) {
  while (parent[std::size_t(v)] != v)
    v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
  return v;
}

}  // namespace

std::vector<std::vector<int>> boundaryLoops(const TriangleMesh& mesh) {
  const int n = mesh.vertexCount();
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (const MeshEdge& e : buildEdges(mesh)) {
    if (e.faces.size() != 1) continue;
    neighbours[std::size_t(e.a)].push_back(e.b);
    neighbours[std::size_t(e.b)].push_back(e.a);
    parent[std::size_t(findRoot(parent, e.a))] = findRoot(parent, e.b);
  }
  // Components, each listed in increasing vertex order (so by first vertex as well).
  std::vector<std::vector<int>> components;
  std::vector<int> componentOfRoot(static_cast<std::size_t>(n), -1);
  for (int v = 0; v < n; ++v) {
    if (neighbours[std::size_t(v)].empty()) continue;
    int& c = componentOfRoot[std::size_t(findRoot(parent, v))];
    if (c < 0) {
      c = int(components.size());
      components.emplace_back();
    }
    components[std::size_t(c)].push_back(v);
  }
  for (std::vector<int>& loop : components) {
    const bool simple = std::all_of(loop.begin(), loop.end(),
                                    [&](int v) { return neighbours[std::size_t(v)].size() == 2; });
    if (!simple) continue;  // stays sorted
    std::vector<int> walk{loop.front()};
    const std::vector<int>& first = neighbours[std::size_t(loop.front())];
    int previous = loop.front(), current = std::min(first[0], first[1]);
    while (current != loop.front()) {
      walk.push_back(current);
      const std::vector<int>& next = neighbours[std::size_t(current)];
      const int following = next[0] == previous ? next[1] : next[0];
      previous = current;
      current = following;
    }
    loop = std::move(walk);
  }
  return components;
}

}  // namespace weft
