#include <weft/render/Bounds.h>

#include <algorithm>

namespace weft::render {

void Bounds::extend(const Vec3f& p) {
  if (!p.allFinite()) return;
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

void Bounds::extend(const Bounds& b) {
  if (b.empty()) return;
  extend(b.min);
  extend(b.max);
}

float Bounds::radius() const {
  if (empty()) return 1.0f;
  return std::max(0.5f * (max - min).norm(), 1e-3f);
}

namespace {

void extendRows(Bounds& b, const PointMatrix& m) {
  for (Eigen::Index i = 0; i < m.rows(); ++i) b.extend(m.row(i).transpose());
}

}  // namespace

float planeHalfSize(const Bounds& bounds) {
  return 2.5f * bounds.radius();
}

Bounds sceneBounds(const RenderScene& scene) {
  Bounds b;
  extendRows(b, scene.cloth.positions);
  for (const ObstacleShape& o : scene.obstacles) {
    switch (o.kind) {
      case ObstacleShape::Kind::Plane:
        break;
      case ObstacleShape::Kind::Sphere:
        b.extend(o.center - Vec3f::Constant(o.radius));
        b.extend(o.center + Vec3f::Constant(o.radius));
        break;
      case ObstacleShape::Kind::Capsule:
      case ObstacleShape::Kind::Cylinder:
        for (const Vec3f& end : {o.a, o.b}) {
          b.extend(end - Vec3f::Constant(o.radius));
          b.extend(end + Vec3f::Constant(o.radius));
        }
        break;
      case ObstacleShape::Kind::Box: {
        const Vec3f reach = o.rotation.cwiseAbs() * o.halfExtents;
        b.extend(o.center - reach);
        b.extend(o.center + reach);
        break;
      }
      case ObstacleShape::Kind::Mesh:
        extendRows(b, o.mesh.positions);
        break;
    }
  }
  for (const auto* points : {&scene.fixedPoints, &scene.handlePoints, &scene.targetPoints})
    for (const Vec3f& p : *points) b.extend(p);
  for (const Curve& c : scene.curves)
    for (const Vec3f& p : c.points) b.extend(p);
  for (const GhostMesh& g : scene.ghosts) extendRows(b, g.mesh.positions);
  return b;
}

}  // namespace weft::render
