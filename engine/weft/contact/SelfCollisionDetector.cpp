#include <weft/contact/SelfCollisionDetector.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>

namespace weft {

SelfCollisionDetector::SelfCollisionDetector(const Scene& scene, const ClothModel& model) {
  const int m = model.nodeCount();
  distance_.assign(m, 0.0);
  friction_.assign(m, 0.0);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    if (!scene.cloths[c].selfCollision || !scene.cloths[c].selfCollision->nodeModel) continue;
    for (int i = model.vertexOffset[c]; i < model.vertexOffset[c + 1]; ++i) {
      distance_[i] = scene.cloths[c].selfCollision->radius;
      friction_[i] = scene.cloths[c].selfCollision->friction;
      nodes_.push_back(i);
    }
  }
  for (int i : nodes_)
    smallestDistance_ =
        smallestDistance_ > 0.0 ? std::min(smallestDistance_, distance_[i]) : distance_[i];
  // One-ring neighbours (nodes sharing a triangle), as sorted CSR lists: the rest-edge graph.
  std::vector<std::pair<int, int>> links;
  links.reserve(6 * model.rest.triangleCount());
  for (int t = 0; t < model.rest.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        if (k != l) links.emplace_back(model.rest.triangles(t, k), model.rest.triangles(t, l));
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  std::vector<int> ringStart(m + 1, 0), ring(links.size());
  for (const auto& l : links) ++ringStart[l.first + 1];
  std::partial_sum(ringStart.begin(), ringStart.end(), ringStart.begin());
  for (std::size_t k = 0; k < links.size(); ++k) ring[k] = links[k].second;

  // Excluded partners of each colliding node: its one ring, and the nodes within the reach at rest
  // that a path of rest edges no longer than kPathFactor times the reach joins to it (Dijkstra
  // bounded by that length). Edges never leave a cloth, so nodes of other cloths are never found.
  // Within one cloth the radius, hence the reach, is the same for every node, and path lengths
  // are symmetric, so the lists are symmetric.
  const auto restPoint = [&](int i) { return Vec3(model.rest.vertices.row(i)); };
  std::vector<std::vector<int>> excluded(m);
  std::vector<double> pathLength(m, std::numeric_limits<double>::infinity());
  std::vector<int> touched;
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int i = 0; i < m; ++i) {
    std::vector<int>& list = excluded[i];
    list.assign(ring.begin() + ringStart[i], ring.begin() + ringStart[i + 1]);
    if (distance_[i] <= 0.0) continue;
    const double reach = (1.0 + kMarginFraction) * distance_[i];
    const double longest = kPathFactor * reach;
    pathLength[i] = 0.0;
    touched.assign(1, i);
    queue.emplace(0.0, i);
    while (!queue.empty()) {
      const auto [length, j] = queue.top();
      queue.pop();
      if (length > pathLength[j]) continue;
      if (j != i && (restPoint(j) - restPoint(i)).norm() < reach) list.push_back(j);
      for (int k = ringStart[j]; k < ringStart[j + 1]; ++k) {
        const int next = ring[k];
        const double through = length + (restPoint(next) - restPoint(j)).norm();
        if (through > longest || through >= pathLength[next]) continue;
        if (std::isinf(pathLength[next])) touched.push_back(next);
        pathLength[next] = through;
        queue.emplace(through, next);
      }
    }
    for (int j : touched) pathLength[j] = std::numeric_limits<double>::infinity();
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  excludedStart_.assign(m + 1, 0);
  for (int i = 0; i < m; ++i)
    excludedStart_[i + 1] = excludedStart_[i] + static_cast<int>(excluded[i].size());
  excluded_.reserve(excludedStart_[m]);
  for (const std::vector<int>& list : excluded)
    excluded_.insert(excluded_.end(), list.begin(), list.end());
}

bool SelfCollisionDetector::excluded(int a, int b) const {
  return std::binary_search(excluded_.begin() + excludedStart_[a],
                            excluded_.begin() + excludedStart_[a + 1], b);
}

void SelfCollisionDetector::detect(const NodeMatrix& x, const NodeMatrix& displacement, double h,
                                   std::vector<ContactPoint>& out) {
  const int n = static_cast<int>(nodes_.size());
  lower_.resize(n);
  upper_.resize(n);
  // The pair test only sees relative motion, so the paths are swept in a frame moving with the
  // nodes' mean displacement: a cloth sliding or falling as a whole then has small boxes.
  Vec3 common = Vec3::Zero();
  for (int k = 0; k < n; ++k) common += displacement.row(nodes_[k]).transpose();
  if (n > 0) common /= n;
  // Swept boxes, padded by half the detection distance: two paths closer than the distance at
  // some tau are then inside both boxes at that tau.
  double extent = 0.0, largestDistance = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : extent) reduction(max : largestDistance)
  for (int k = 0; k < n; ++k) {
    const int i = nodes_[k];
    const Vec3 a = x.row(i), b = a + Vec3(displacement.row(i)) - common;
    const double pad = 0.5 * (1.0 + kMarginFraction) * distance_[i];
    lower_[k] = a.cwiseMin(b) - Vec3::Constant(pad);
    upper_[k] = a.cwiseMax(b) + Vec3::Constant(pad);
    extent += (upper_[k] - lower_[k]).maxCoeff();
    largestDistance = std::max(largestDistance, (1.0 + kMarginFraction) * distance_[i]);
  }
  // Cells twice the size of a typical box: O(1) cells per box and O(1) boxes per cell. Cells of
  // one box size put each box in about 8 cells, and the table's scattered writes then cost more
  // than the extra pair tests of larger cells (docs/how-it-works/contact.md).
  const double cell = kCellOverBoxSize * std::max(n > 0 ? extent / n : 0.0, largestDistance);
  candidates_.clear();
  if (n > 1) grid_.overlappingPairs(lower_, upper_, cell, candidates_);
  lastCandidates_ = static_cast<int>(candidates_.size());

  const int count = static_cast<int>(candidates_.size());
  const std::size_t first = out.size();
  collector_.collect(count, out, [&](int p, std::vector<ContactPoint>& local) {
    const int a = nodes_[candidates_[p].first], b = nodes_[candidates_[p].second];
    const double distance = collisionDistance(a, b);
    const Vec3 dx = x.row(a) - x.row(b);
    const Vec3 dd = displacement.row(a) - displacement.row(b);
    const double dd2 = dd.squaredNorm();
    const double tau = dd2 > 0.0 ? std::clamp(-dx.dot(dd) / dd2, 0.0, 1.0) : 0.0;
    if ((dx + tau * dd).norm() >= (1.0 + kMarginFraction) * distance) return;
    if (excluded(a, b)) return;
    ContactPoint c;
    c.node = a;
    c.partner = b;
    const double separation = dx.norm();
    if (separation > 1e-12 * distance)
      c.normal = dx / separation;
    else if (dd2 > 0.0)
      c.normal = -dd.normalized();  // coincident nodes: separate against their approach
    else
      c.normal = Vec3::UnitY();
    c.friction = 0.5 * (friction_[a] + friction_[b]);
    c.reference = -((separation - distance) / h) * c.normal;
    local.push_back(c);
  });
  std::sort(out.begin() + first, out.end(), [](const ContactPoint& p, const ContactPoint& q) {
    return p.node != q.node ? p.node < q.node : p.partner < q.partner;
  });
}

}  // namespace weft
