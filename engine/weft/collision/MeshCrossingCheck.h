#pragma once
// How many edges of the self-colliding cloths pass through a triangle of them at a state: the
// check, independent of continuous collision detection, that a run is free of crossings
// (stats.csv's `crossings`, summary.json's "crossings"). Edges and triangles that share a vertex
// are not counted.

#include <weft/collision/CollisionMesh.h>

#include <utility>

namespace weft::collision {

class MeshCrossingCheck {
 public:
  explicit MeshCrossingCheck(CollisionMesh mesh) : mesh_(std::move(mesh)) {}
  // Edge-triangle crossings at the global positions (all nodes of the cloth model, m x 3).
  int count(const NodeMatrix& global) const;

 private:
  CollisionMesh mesh_;
  mutable NodeMatrix local_;
};

}  // namespace weft::collision
