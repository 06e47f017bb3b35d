#pragma once
// A triangle-mesh obstacle (any mesh the loaders read), queried through a TriangleBvh.
// Distance: to the nearest point of the surface, signed by the angle-weighted pseudo-normal of
// the nearest feature (Baerentzen and Aanaes 2005), which is exact inside/outside for a closed,
// consistently oriented mesh. Normal: either the nearest triangle's face normal (piecewise
// constant: the "discretized" sphere of DiffCloth Fig. 2, whose jumps make the dynamics
// discontinuous) or, with smooth normals, the vertex normals interpolated barycentrically at the
// nearest point (continuous over the surface, Sec. 5.1's remedy).

#include <weft/contact/ObstacleShape.h>
#include <weft/contact/TriangleBvh.h>

#include <array>
#include <vector>

namespace weft {

class MeshShape final : public ObstacleShape {
 public:
  MeshShape(const TriangleMesh& mesh, bool smoothNormals);
  const char* name() const override { return "mesh"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;
  const TriangleBvh& bvh() const { return bvh_; }

 private:
  TriangleMesh mesh_;
  TriangleBvh bvh_;
  bool smooth_;
  std::vector<Vec3> faceNormals_;                 // unit (zero for degenerate triangles)
  std::vector<Vec3> vertexNormals_;               // angle-weighted pseudo-normals, unit
  std::vector<std::array<Vec3, 3>> edgeNormals_;  // per triangle edge k (corner k -> k+1)
};

}  // namespace weft
