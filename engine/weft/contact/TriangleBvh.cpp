#include <weft/contact/TriangleBvh.h>

#include <weft/core/Error.h>

#include <algorithm>
#include <limits>

namespace weft {
namespace {

constexpr int kLeafSize = 4;
constexpr int kMaxDepth = 60;  // the traversal stack holds one pending child per level

double squaredDistanceToBox(const Vec3& p, const Vec3& lower, const Vec3& upper) {
  const Vec3 below = (lower - p).cwiseMax(0.0), above = (p - upper).cwiseMax(0.0);
  return (below + above).squaredNorm();
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& bary,
                            TriangleFeature& feature) {
  // Voronoi regions of the triangle's features, tested in order (vertices, edges, face), from
  // the signs of dot products of p - corner with the edge vectors.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    bary = Vec3(1, 0, 0), feature = TriangleFeature::Vertex0;
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    bary = Vec3(0, 1, 0), feature = TriangleFeature::Vertex1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    bary = Vec3(1 - t, t, 0), feature = TriangleFeature::Edge01;
    return a + t * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    bary = Vec3(0, 0, 1), feature = TriangleFeature::Vertex2;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    bary = Vec3(1 - t, 0, t), feature = TriangleFeature::Edge20;
    return a + t * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = Vec3(0, 1 - t, t), feature = TriangleFeature::Edge12;
    return b + t * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // degenerate (zero-area) triangle: fall back to its nearest corner
    const double da = ap.squaredNorm(), db = bp.squaredNorm(), dc = cp.squaredNorm();
    if (da <= db && da <= dc) return bary = Vec3(1, 0, 0), feature = TriangleFeature::Vertex0, a;
    if (db <= dc) return bary = Vec3(0, 1, 0), feature = TriangleFeature::Vertex1, b;
    return bary = Vec3(0, 0, 1), feature = TriangleFeature::Vertex2, c;
  }
  const double v = vb / sum, w = vc / sum;
  bary = Vec3(1 - v - w, v, w), feature = TriangleFeature::Face;
  return a + v * ab + w * ac;
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh)
    : vertices_(mesh.vertices), triangles_(mesh.triangles) {
  const int n = mesh.triangleCount();
  if (n == 0) throw InputError("mesh obstacle", "mesh", "has no triangles");
  std::vector<Vec3> centroids(n);
  order_.resize(n);
  for (int t = 0; t < n; ++t) {
    order_[t] = t;
    centroids[t] = (vertices_.row(triangles_(t, 0)) + vertices_.row(triangles_(t, 1)) +
                    vertices_.row(triangles_(t, 2)))
                       .transpose() /
                   3.0;
  }
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(0, n, centroids, 0);
}

int TriangleBvh::build(int first, int count, std::vector<Vec3>& centroids, int depth) {
  depth_ = std::max(depth_, depth);
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity()), upper = -lower;
  Vec3 cLower = lower, cUpper = upper;
  for (int i = first; i < first + count; ++i) {
    const int t = order_[i];
    for (int k = 0; k < 3; ++k) {
      const Vec3 v = vertices_.row(triangles_(t, k));
      lower = lower.cwiseMin(v), upper = upper.cwiseMax(v);
    }
    cLower = cLower.cwiseMin(centroids[t]), cUpper = cUpper.cwiseMax(centroids[t]);
  }
  nodes_[index].lower = lower;
  nodes_[index].upper = upper;
  if (count <= kLeafSize || depth >= kMaxDepth) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  (cUpper - cLower).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  const int left = build(first, half, centroids, depth + 1);
  const int right = build(first + half, count - half, centroids, depth + 1);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

bool TriangleBvh::nearest(const Vec3& p, double maxSquaredDistance, Nearest& out) const {
  double best = maxSquaredDistance;
  bool found = false;
  int stack[kMaxDepth + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (squaredDistanceToBox(p, node.lower, node.upper) >= best) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[i];
        Vec3 bary;
        TriangleFeature feature;
        const Vec3 q = closestPointOnTriangle(p, vertices_.row(triangles_(t, 0)),
                                              vertices_.row(triangles_(t, 1)),
                                              vertices_.row(triangles_(t, 2)), bary, feature);
        const double d = (p - q).squaredNorm();
        if (d < best) {
          best = d;
          found = true;
          out.triangle = t, out.point = q, out.barycentric = bary, out.feature = feature,
          out.squaredDistance = d;
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last) so that `best` shrinks early.
    const Node& l = nodes_[node.left];
    const Node& r = nodes_[node.right];
    const double dl = squaredDistanceToBox(p, l.lower, l.upper),
                 dr = squaredDistanceToBox(p, r.lower, r.upper);
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return found;
}

}  // namespace weft
