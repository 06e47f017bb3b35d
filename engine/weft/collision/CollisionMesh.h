#pragma once
// The cloths that take part in surface collisions, as one triangle mesh of their own: the
// vertices of the chosen cloths in scene order, their triangles re-indexed, and each vertex's
// global node. Impact zones (Liang 2019) act on it, and the edge-triangle crossing check counts
// on it; between cloths it is one mesh, so two cloths collide with each other as with
// themselves.

#include <weft/core/Types.h>
#include <weft/mesh/TriangleMesh.h>
#include <weft/model/ClothModel.h>
#include <weft/scene/Scene.h>

#include <vector>

namespace weft::collision {

struct CollisionMesh {
  TriangleMesh mesh;       // rest positions, local triangles
  std::vector<int> nodes;  // global node of each local vertex
  Eigen::VectorXd mass;    // kg per local vertex (the cloth model's lumped masses)

  // The cloths with any self_collision model, or (impactZonesOnly) with "impact_zones".
  static CollisionMesh of(const Scene& scene, const ClothModel& model, bool impactZonesOnly);

  int vertexCount() const { return static_cast<int>(nodes.size()); }
  bool empty() const { return nodes.empty(); }
  // Local positions from the global ones, and back.
  void gather(const NodeMatrix& global, NodeMatrix& local) const;
  void scatter(const NodeMatrix& local, NodeMatrix& global) const;
};

}  // namespace weft::collision
