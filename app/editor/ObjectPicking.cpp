#include "ObjectPicking.h"

#include "ClothNodes.h"

#include <weft/render/ShapeTessellation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::editor {
namespace {

// Enough for a ray that skims a plane at a shallow angle (each step then gains only the sine of
// the angle times the height) to still find it; a ray that needs more is a silhouette graze.
constexpr int kMaxSteps = 4000;

}  // namespace

std::optional<double> traceShape(const ObstacleShape& shape, const RigidPose& pose, const Ray& ray,
                                 double maxDistance) {
  const Vec3 origin = ray.origin.cast<double>(),
             direction = ray.direction.cast<double>().normalized();
  const double infinity = std::numeric_limits<double>::infinity();
  double t = 0.0;
  for (int step = 0; step < kMaxSteps && t <= maxDistance; ++step) {
    SurfaceSample sample;
    if (!shape.sample(pose.inverse(origin + t * direction), infinity, sample)) return std::nullopt;
    // The magnitude: a ray that starts inside (the camera within a box, under the ground) still
    // walks to the surface it sees.
    const double distance = std::abs(sample.distance);
    if (!std::isfinite(distance)) return std::nullopt;
    // Far below a pixel at that depth: the hit is found to well within what a click can tell.
    if (distance <= 1e-6 + 1e-6 * t) return t;
    t += distance;
  }
  return std::nullopt;
}

namespace {

bool insideDrawnSquare(const Obstacle& plane, const RigidPose& pose, const DrawnPlaneExtent& extent,
                       const Vec3& hit) {
  const Vec3 normal = (pose.rotation * plane.normal).normalized();
  const Vec3 point = pose.apply(plane.point);
  const Vec3 centre = extent.centre - (extent.centre - point).dot(normal) * normal;
  render::Vec3f e1, e2;
  render::perpendicularFrame(normal.cast<float>(), e1, e2);
  const Vec3 d = hit - centre;
  return std::abs(d.dot(e1.cast<double>())) <= extent.halfSize &&
         std::abs(d.dot(e2.cast<double>())) <= extent.halfSize;
}

}  // namespace

std::optional<ObjectHit> pickObject(const Scene& scene, double time,
                                    const render::SurfaceMesh& cloth, const Ray& ray,
                                    double maxDistance,
                                    const std::optional<DrawnPlaneExtent>& planes) {
  std::optional<ObjectHit> best;
  auto offer = [&](EditorObject::Kind kind, int index, double distance) {
    if (best && best->distance <= distance) return;
    EditorObject object;
    object.kind = kind;
    object.index = index;
    best = ObjectHit{object, distance};
  };
  for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
    const Obstacle& o = scene.obstacles[k];
    const std::unique_ptr<ObstacleShape> shape = makeObstacleShape(o);
    if (!shape) continue;
    // Where the viewport draws it: the frame builder moves an obstacle by the same motion.
    const RigidPose pose = o.motion ? poseAt(*o.motion, time) : RigidPose();
    if (const auto t = traceShape(*shape, pose, ray, maxDistance)) {
      const Vec3 hit = ray.origin.cast<double>() + *t * ray.direction.cast<double>().normalized();
      if (o.shape == Obstacle::Shape::Plane && planes && !insideDrawnSquare(o, pose, *planes, hit))
        continue;
      offer(EditorObject::Kind::Obstacle, int(k), *t);
    }
  }
  const std::vector<int> offsets = clothVertexOffsets(scene);
  if (cloth.positions.rows() == offsets.back()) {
    const auto hit = nearestTriangleHit(cloth, ray);
    if (hit && hit->distance <= maxDistance) {
      const int vertex = cloth.triangles(hit->triangle, 0);
      offer(EditorObject::Kind::Cloth, clothOfNode(offsets, vertex), hit->distance);
    }
  }
  return best;
}

}  // namespace weft::editor
