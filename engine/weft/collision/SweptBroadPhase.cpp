#include <weft/collision/SweptBroadPhase.h>

#include <omp.h>

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace weft::collision {
namespace {

constexpr int kLeafSize = 4;
constexpr int kMaxDepth = 60;

bool overlap(const Vec3& la, const Vec3& ua, const Vec3& lb, const Vec3& ub) {
  return (la.array() <= ub.array()).all() && (lb.array() <= ua.array()).all();
}

bool candidateLess(const CcdCandidate& a, const CcdCandidate& b) {
  return std::tie(a.kind, a.nodes) < std::tie(b.kind, b.nodes);
}

}  // namespace

bool impactLess(const Impact& a, const Impact& b) {
  return std::tie(a.time, a.kind, a.nodes) < std::tie(b.time, b.kind, b.nodes);
}

SweptBroadPhase::SweptBroadPhase(const TriangleMesh& mesh, std::vector<bool> staticVertex)
    : vertexCount_(mesh.vertexCount()),
      triangles_(mesh.triangles),
      edges_(buildEdges(mesh)),
      static_(std::move(staticVertex)) {
  if (!static_.empty() && static_.size() != static_cast<std::size_t>(vertexCount_))
    throw std::invalid_argument("SweptBroadPhase: one static flag per vertex expected");
  const int n = mesh.triangleCount();
  // Ownership: a vertex by the first triangle containing it, an edge by its first face.
  triangleVertices_.assign(n, {{-1, -1, -1}});
  triangleEdges_.assign(n, {{-1, -1, -1}});
  std::vector<char> owned(vertexCount_, 0);
  for (int t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c) {
      const int v = triangles_(t, c);
      if (!owned[v]) owned[v] = 1, triangleVertices_[t][c] = v;
    }
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    auto& slots = triangleEdges_[edges_[e].faces.front()];
    *std::find(slots.begin(), slots.end(), -1) = e;
  }
  if (n == 0) return;
  std::vector<Vec3> centroids(n);
  order_.resize(n);
  for (int t = 0; t < n; ++t) {
    order_[t] = t;
    centroids[t] = (mesh.vertices.row(triangles_(t, 0)) + mesh.vertices.row(triangles_(t, 1)) +
                    mesh.vertices.row(triangles_(t, 2)))
                       .transpose() /
                   3.0;
  }
  nodes_.reserve(2 * n);
  build(0, n, centroids, 0);
  triLower_.resize(n);
  triUpper_.resize(n);
}

int SweptBroadPhase::build(int first, int count, const std::vector<Vec3>& centroids, int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  if (count <= kLeafSize || depth >= kMaxDepth) {
    nodes_[index].first = first, nodes_[index].count = count;
    return index;
  }
  Vec3 lo = centroids[order_[first]], hi = lo;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(centroids[order_[i]]);
    hi = hi.cwiseMax(centroids[order_[i]]);
  }
  int axis;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int a, int b) {
                     return std::make_pair(centroids[a][axis], a) <
                            std::make_pair(centroids[b][axis], b);
                   });
  const int left = build(first, mid - first, centroids, depth + 1);
  const int right = build(mid, first + count - mid, centroids, depth + 1);
  nodes_[index].left = left, nodes_[index].right = right;
  return index;
}

void SweptBroadPhase::refit(const NodeMatrix& start, const NodeMatrix& end, double thickness) {
  const int n = static_cast<int>(triangles_.rows());
  const Vec3 pad = Vec3::Constant(thickness);
  for (int t = 0; t < n; ++t) {
    Vec3 lo = start.row(triangles_(t, 0)).transpose(), hi = lo;
    for (int c = 0; c < 3; ++c) {
      const Vec3 a = start.row(triangles_(t, c)).transpose(),
                 b = end.row(triangles_(t, c)).transpose();
      lo = lo.cwiseMin(a).cwiseMin(b);
      hi = hi.cwiseMax(a).cwiseMax(b);
    }
    triLower_[t] = lo - pad, triUpper_[t] = hi + pad;
  }
  // Children are stored after their parent: a reverse sweep refits bottom-up.
  for (int i = static_cast<int>(nodes_.size()) - 1; i >= 0; --i) {
    Node& node = nodes_[i];
    if (node.left < 0) {
      node.lower = triLower_[order_[node.first]], node.upper = triUpper_[order_[node.first]];
      for (int k = node.first + 1; k < node.first + node.count; ++k) {
        node.lower = node.lower.cwiseMin(triLower_[order_[k]]);
        node.upper = node.upper.cwiseMax(triUpper_[order_[k]]);
      }
    } else {
      node.lower = nodes_[node.left].lower.cwiseMin(nodes_[node.right].lower);
      node.upper = nodes_[node.left].upper.cwiseMax(nodes_[node.right].upper);
    }
  }
}

void SweptBroadPhase::trianglePair(int t1, int t2) {
  auto isStatic = [&](int v) { return !static_.empty() && static_[v]; };
  auto emit = [&](ImpactKind kind, const std::array<int, 4>& nodes) {
    if (isStatic(nodes[0]) && isStatic(nodes[1]) && isStatic(nodes[2]) && isStatic(nodes[3]))
      return;
    candidates_.push_back({kind, nodes});
  };
  auto corner = [&](int t, int v) {
    return triangles_(t, 0) == v || triangles_(t, 1) == v || triangles_(t, 2) == v;
  };
  for (int pass = 0; pass < 2; ++pass) {
    const int owner = pass == 0 ? t1 : t2, face = pass == 0 ? t2 : t1;
    for (int v : triangleVertices_[owner])
      if (v >= 0 && !corner(face, v))
        emit(ImpactKind::VertexFace,
             {v, triangles_(face, 0), triangles_(face, 1), triangles_(face, 2)});
  }
  for (int e1 : triangleEdges_[t1]) {
    if (e1 < 0) continue;
    for (int e2 : triangleEdges_[t2]) {
      if (e2 < 0) continue;
      const MeshEdge &a = edges_[std::min(e1, e2)], &b = edges_[std::max(e1, e2)];
      if (a.a == b.a || a.a == b.b || a.b == b.a || a.b == b.b) continue;
      emit(ImpactKind::EdgeEdge, {a.a, a.b, b.a, b.b});
    }
  }
}

void SweptBroadPhase::leafPairs(const Node& a, const Node& b) {
  const bool same = &a == &b;
  for (int i = a.first; i < a.first + a.count; ++i)
    for (int j = same ? i + 1 : b.first; j < b.first + b.count; ++j) {
      const int t1 = order_[i], t2 = order_[j];
      if (overlap(triLower_[t1], triUpper_[t1], triLower_[t2], triUpper_[t2])) trianglePair(t1, t2);
    }
}

const std::vector<CcdCandidate>& SweptBroadPhase::findCandidates(const NodeMatrix& start,
                                                                 const NodeMatrix& end,
                                                                 double thickness) {
  if (start.rows() != vertexCount_ || end.rows() != vertexCount_)
    throw std::invalid_argument("SweptBroadPhase: one position row per vertex expected");
  candidates_.clear();
  if (nodes_.empty()) return candidates_;
  refit(start, end, thickness);
  // Self-traversal: a node against itself descends into (left, left), (right, right) and
  // (left, right); two distinct nodes are pruned when their boxes do not overlap.
  stack_.clear();
  stack_.emplace_back(0, 0);
  while (!stack_.empty()) {
    const auto [ia, ib] = stack_.back();
    stack_.pop_back();
    const Node &a = nodes_[ia], &b = nodes_[ib];
    if (ia == ib) {
      if (a.left < 0) {
        leafPairs(a, a);
      } else {
        stack_.emplace_back(a.left, a.left);
        stack_.emplace_back(a.right, a.right);
        stack_.emplace_back(a.left, a.right);
      }
      continue;
    }
    if (!overlap(a.lower, a.upper, b.lower, b.upper)) continue;
    if (a.left < 0 && b.left < 0) {
      leafPairs(a, b);
    } else if (a.left < 0) {  // descend the inner node
      stack_.emplace_back(ia, b.left);
      stack_.emplace_back(ia, b.right);
    } else {
      stack_.emplace_back(a.left, ib);
      stack_.emplace_back(a.right, ib);
    }
  }
  std::sort(candidates_.begin(), candidates_.end(), candidateLess);
  return candidates_;
}

std::vector<Impact> SweptBroadPhase::findImpacts(const NodeMatrix& start, const NodeMatrix& end,
                                                 double thickness) {
  const std::vector<CcdCandidate>& candidates = findCandidates(start, end, thickness);
  const int count = static_cast<int>(candidates.size());
  perThread_.resize(std::max(1, omp_get_max_threads()));
  for (auto& local : perThread_) local.clear();
#pragma omp parallel
  {
    std::vector<Impact>& local = perThread_[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < count; ++i) {
      const CcdCandidate& c = candidates[i];
      PairPositions a, b;
      for (int k = 0; k < 4; ++k) {
        a[k] = start.row(c.nodes[k]).transpose();
        b[k] = end.row(c.nodes[k]).transpose();
      }
      if (auto impact = pairCcd(c.kind, a, b, thickness)) {
        impact->nodes = c.nodes;
        local.push_back(*impact);
      }
    }
  }
  std::vector<Impact> impacts;
  std::size_t total = 0;
  for (const auto& local : perThread_) total += local.size();
  impacts.reserve(total);
  for (const auto& local : perThread_) impacts.insert(impacts.end(), local.begin(), local.end());
  std::sort(impacts.begin(), impacts.end(), impactLess);
  return impacts;
}

}  // namespace weft::collision
