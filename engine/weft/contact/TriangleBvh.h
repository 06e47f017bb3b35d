#pragma once
// A bounding-volume hierarchy of axis-aligned boxes over the triangles of a mesh, for nearest-
// point queries (the acceleration structure of mesh obstacles). Built once, top-down, by median
// splits of the triangle centroids along the widest axis; queried concurrently without
// allocation.

#include <weft/mesh/TriangleMesh.h>

#include <vector>

namespace weft {

// Where on a triangle the closest point lies: a vertex (0-2), an edge (3 + k for the edge from
// corner k to corner k+1 mod 3) or the interior (6).
enum class TriangleFeature : int { Vertex0 = 0, Vertex1, Vertex2, Edge01, Edge12, Edge20, Face };

// Closest point of triangle (a, b, c) to p, with its barycentric coordinates and feature.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                            Vec3& barycentric, TriangleFeature& feature);

class TriangleBvh {
 public:
  struct Nearest {
    int triangle = -1;
    Vec3 point = Vec3::Zero();
    Vec3 barycentric = Vec3::Zero();
    TriangleFeature feature = TriangleFeature::Face;
    double squaredDistance = 0.0;
  };

  TriangleBvh() = default;
  explicit TriangleBvh(const TriangleMesh& mesh);

  // The nearest point of the mesh to p closer than sqrt(maxSquaredDistance) (infinity for an
  // unbounded query). Returns false when there is none.
  bool nearest(const Vec3& p, double maxSquaredDistance, Nearest& out) const;
  const Vec3& lower() const { return nodes_.front().lower; }
  const Vec3& upper() const { return nodes_.front().upper; }
  int depth() const { return depth_; }

 private:
  struct Node {
    Vec3 lower, upper;
    int first = 0, count = 0;   // leaf: triangles order_[first, first + count)
    int left = -1, right = -1;  // inner node children
  };
  int build(int first, int count, std::vector<Vec3>& centroids, int depth);

  NodeMatrix vertices_;
  TriangleIndices triangles_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
  int depth_ = 0;
};

}  // namespace weft
