#include <weft/contact/ContactLayering.h>

#include <algorithm>
#include <numeric>

namespace weft {

void ContactLayering::order(std::vector<ContactPoint>& pairs, const std::vector<int>& obstacleNodes,
                            std::vector<int>& layerStart) {
  layerStart.assign(1, 0);
  const int count = static_cast<int>(pairs.size());
  if (count == 0) return;

  // Nodes of the pair graph, numbered densely, and their adjacency (pair indices).
  touched_.clear();
  for (const ContactPoint& p : pairs)
    for (int v : {p.node, p.partner})
      if (slot_[v] < 0) slot_[v] = static_cast<int>(touched_.size()), touched_.push_back(v);
  const int n = static_cast<int>(touched_.size());
  adjacencyStart_.assign(n + 1, 0);
  for (const ContactPoint& p : pairs)
    ++adjacencyStart_[slot_[p.node] + 1], ++adjacencyStart_[slot_[p.partner] + 1];
  std::partial_sum(adjacencyStart_.begin(), adjacencyStart_.end(), adjacencyStart_.begin());
  adjacency_.resize(2 * count);
  orderBuffer_.assign(adjacencyStart_.begin(), adjacencyStart_.end() - 1);
  for (int e = 0; e < count; ++e) {
    adjacency_[orderBuffer_[slot_[pairs[e].node]]++] = e;
    adjacency_[orderBuffer_[slot_[pairs[e].partner]]++] = e;
  }

  // Breadth-first levels: from obstacle-contact nodes, then chain ends, then anything left. A
  // later phase's levels come after all earlier ones.
  int base = 0;
  auto bfs = [&](auto&& isSource) {
    queue_.clear();
    for (int s = 0; s < n; ++s)
      if (level_[touched_[s]] < 0 && isSource(s)) level_[touched_[s]] = base, queue_.push_back(s);
    int deepest = base - 1;
    for (std::size_t q = 0; q < queue_.size(); ++q) {
      const int s = queue_[q];
      const int l = level_[touched_[s]];
      deepest = std::max(deepest, l);
      for (int k = adjacencyStart_[s]; k < adjacencyStart_[s + 1]; ++k) {
        const ContactPoint& p = pairs[adjacency_[k]];
        const int other = slot_[p.node] == s ? slot_[p.partner] : slot_[p.node];
        if (level_[touched_[other]] < 0) level_[touched_[other]] = l + 1, queue_.push_back(other);
      }
    }
    base = deepest + 1;
  };
  for (int v : obstacleNodes)
    if (slot_[v] >= 0) level_[v] = -2;  // mark as source
  bfs([&](int s) { return level_[touched_[s]] == -2 ? (level_[touched_[s]] = -1, true) : false; });
  bfs([&](int s) { return adjacencyStart_[s + 1] - adjacencyStart_[s] == 1; });
  for (int s = 0; s < n; ++s)
    if (level_[touched_[s]] < 0) bfs([&](int t) { return t == s; });

  // Visiting order by the nearer endpoint's level (stable: ties keep the detection order).
  pairKey_.resize(count);
  for (int e = 0; e < count; ++e)
    pairKey_[e] = std::min(level_[pairs[e].node], level_[pairs[e].partner]);
  orderBuffer_.resize(count);
  std::iota(orderBuffer_.begin(), orderBuffer_.end(), 0);
  std::stable_sort(orderBuffer_.begin(), orderBuffer_.end(),
                   [&](int a, int b) { return pairKey_[a] < pairKey_[b]; });

  // Greedy layers, then a counting sort by layer.
  pairLayer_.resize(count);
  int layers = 0;
  for (int e : orderBuffer_) {
    const ContactPoint& p = pairs[e];
    const int layer = std::max(last_[p.node], last_[p.partner]) + 1;
    last_[p.node] = last_[p.partner] = layer;
    pairLayer_[e] = layer;
    layers = std::max(layers, layer + 1);
  }
  layerStart.assign(layers + 1, 0);
  for (int e = 0; e < count; ++e) ++layerStart[pairLayer_[e] + 1];
  std::partial_sum(layerStart.begin(), layerStart.end(), layerStart.begin());
  queue_.assign(layerStart.begin(), layerStart.end() - 1);  // reuse as cursors
  sorted_.resize(count);
  for (int e : orderBuffer_) sorted_[queue_[pairLayer_[e]]++] = pairs[e];
  pairs.swap(sorted_);

  for (int v : touched_) level_[v] = -1, last_[v] = -1, slot_[v] = -1;
  for (int v : obstacleNodes) level_[v] = -1;
}

}  // namespace weft
