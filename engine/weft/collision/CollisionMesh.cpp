#include <weft/collision/CollisionMesh.h>

namespace weft::collision {

CollisionMesh CollisionMesh::of(const Scene& scene, const ClothModel& model, bool impactZonesOnly) {
  CollisionMesh out;
  std::vector<int> triangles;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const auto& sc = scene.cloths[c].selfCollision;
    if (!sc || (impactZonesOnly && !sc->impactZones)) continue;
    const int offset = model.vertexOffset[c], local = out.vertexCount();
    for (int i = offset; i < model.vertexOffset[c + 1]; ++i) out.nodes.push_back(i);
    for (int t = model.triangleOffset[c]; t < model.triangleOffset[c + 1]; ++t)
      for (int k = 0; k < 3; ++k) triangles.push_back(model.rest.triangles(t, k) - offset + local);
  }
  const int m = out.vertexCount();
  out.mesh.vertices.resize(m, 3);
  out.mass.resize(m);
  for (int i = 0; i < m; ++i) {
    out.mesh.vertices.row(i) = model.rest.vertices.row(out.nodes[i]);
    out.mass[i] = model.mass[out.nodes[i]];
  }
  out.mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size() / 3), 3);
  for (std::size_t k = 0; k < triangles.size(); ++k)
    out.mesh.triangles(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) =
        triangles[k];
  return out;
}

void CollisionMesh::gather(const NodeMatrix& global, NodeMatrix& local) const {
  local.resize(vertexCount(), 3);
  for (int i = 0; i < vertexCount(); ++i) local.row(i) = global.row(nodes[i]);
}

void CollisionMesh::scatter(const NodeMatrix& local, NodeMatrix& global) const {
  for (int i = 0; i < vertexCount(); ++i) global.row(nodes[i]) = local.row(i);
}

}  // namespace weft::collision
