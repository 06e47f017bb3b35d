#include <weft/contact/MeshShape.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft {

MeshShape::MeshShape(const TriangleMesh& mesh, bool smoothNormals)
    : mesh_(mesh), bvh_(mesh), smooth_(smoothNormals) {
  const int n = mesh.triangleCount();
  faceNormals_.assign(n, Vec3::Zero());
  vertexNormals_.assign(mesh.vertexCount(), Vec3::Zero());
  for (int t = 0; t < n; ++t) {
    const Vec3 p[3] = {mesh.vertices.row(mesh.triangles(t, 0)),
                       mesh.vertices.row(mesh.triangles(t, 1)),
                       mesh.vertices.row(mesh.triangles(t, 2))};
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double area2 = cross.norm();
    if (!(area2 > 0.0)) continue;
    faceNormals_[t] = cross / area2;
    for (int k = 0; k < 3; ++k) {
      const Vec3 e1 = (p[(k + 1) % 3] - p[k]).normalized(),
                 e2 = (p[(k + 2) % 3] - p[k]).normalized();
      const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
      vertexNormals_[mesh.triangles(t, k)] += angle * faceNormals_[t];
    }
  }
  for (Vec3& v : vertexNormals_)
    if (v.norm() > 0.0) v.normalize();

  // Edge pseudo-normals: the sum of the normals of the triangles sharing the edge.
  const std::vector<MeshEdge> edges = buildEdges(mesh);
  edgeNormals_.assign(n, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) {
      int a = mesh.triangles(t, k), b = mesh.triangles(t, (k + 1) % 3);
      if (a > b) std::swap(a, b);
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(a, b),
                                       [](const MeshEdge& e, const std::pair<int, int>& key) {
                                         return std::make_pair(e.a, e.b) < key;
                                       });
      Vec3 sum = Vec3::Zero();
      for (int f : it->faces) sum += faceNormals_[f];
      edgeNormals_[t][k] = sum.norm() > 0.0 ? Vec3(sum.normalized()) : faceNormals_[t];
    }
  }
}

bool MeshShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  // Farther than `reach` outside the mesh's box: certainly farther from the surface.
  const Vec3 below = (bvh_.lower() - p).cwiseMax(0.0), above = (p - bvh_.upper()).cwiseMax(0.0);
  if ((below + above).squaredNorm() > reach * reach) return false;
  // Unbounded query: a point deep inside (after a fast impact) must still find its way out.
  TriangleBvh::Nearest nearest;
  if (!bvh_.nearest(p, std::numeric_limits<double>::infinity(), nearest)) return false;
  const int t = nearest.triangle;
  const int f = static_cast<int>(nearest.feature);
  Vec3 pseudo;
  if (f <= 2)
    pseudo = vertexNormals_[mesh_.triangles(t, f)];
  else if (f <= 5)
    pseudo = edgeNormals_[t][f - 3];
  else
    pseudo = faceNormals_[t];
  const Vec3 offset = p - nearest.point;
  const double unsignedDistance = std::sqrt(nearest.squaredDistance);
  const double distance = offset.dot(pseudo) < 0.0 ? -unsignedDistance : unsignedDistance;
  if (distance > reach) return false;
  Vec3 normal = faceNormals_[t];
  if (smooth_) {
    const Vec3& b = nearest.barycentric;
    const Vec3 blend = b[0] * vertexNormals_[mesh_.triangles(t, 0)] +
                       b[1] * vertexNormals_[mesh_.triangles(t, 1)] +
                       b[2] * vertexNormals_[mesh_.triangles(t, 2)];
    if (blend.norm() > 1e-12) normal = blend.normalized();
  }
  if (normal.squaredNorm() == 0.0) normal = pseudo.squaredNorm() > 0.0 ? pseudo : Vec3::UnitY();
  out.distance = distance;
  out.normal = normal;
  out.point = nearest.point;
  return true;
}

}  // namespace weft
