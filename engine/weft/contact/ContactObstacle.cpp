#include <weft/contact/ContactObstacle.h>

#include <weft/contact/BoxShape.h>
#include <weft/contact/CapsuleShape.h>
#include <weft/contact/CylinderShape.h>
#include <weft/contact/MeshShape.h>
#include <weft/contact/PlaneShape.h>
#include <weft/contact/SphereShape.h>

#include <utility>

namespace weft {

RigidPose poseAt(const HandleTrajectory& motion, double t) {
  // target() is affine in the body point: read its linear part from the unit vectors.
  RigidPose pose;
  pose.translation = motion.target(Vec3::Zero(), t);
  for (int k = 0; k < 3; ++k)
    pose.rotation.col(k) = motion.target(Vec3::Unit(k), t) - pose.translation;
  return pose;
}

std::unique_ptr<ObstacleShape> makeObstacleShape(const Obstacle& o) {
  switch (o.shape) {
    case Obstacle::Shape::Plane:
      return std::make_unique<PlaneShape>(o.point, o.normal);
    case Obstacle::Shape::Sphere:
      return std::make_unique<SphereShape>(o.center, o.radius);
    case Obstacle::Shape::Capsule:
      return std::make_unique<CapsuleShape>(o.a, o.b, o.radius);
    case Obstacle::Shape::Box:
      return std::make_unique<BoxShape>(o.center, o.halfExtents, o.rotation);
    case Obstacle::Shape::Cylinder:
      return std::make_unique<CylinderShape>(o.a, o.b, o.radius);
    case Obstacle::Shape::Mesh:
      return std::make_unique<MeshShape>(o.mesh, o.smoothNormals);
  }
  return nullptr;
}

ContactObstacle::ContactObstacle(const Obstacle& o, std::shared_ptr<const ObstacleShape> shape)
    : shape_(std::move(shape)), motion_(o.motion), friction_(o.friction), thickness_(o.thickness) {}

void ContactObstacle::beginStep(double t0, double t1) {
  h_ = t1 - t0;
  if (!motion_) return;
  start_ = poseAt(*motion_, t0);
  end_ = poseAt(*motion_, t1);
}

bool ContactObstacle::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  if (!motion_) return shape_->sample(p, reach, out);
  if (!shape_->sample(end_.inverse(p), reach, out)) return false;
  out.normal = end_.rotation * out.normal;
  out.point = end_.apply(out.point);
  return true;
}

bool ContactObstacle::sample(const Vec3& p, const Vec3& start, double reach,
                             SurfaceSample& out) const {
  if (!motion_) return shape_->sampleMoved(p, start, reach, out);
  if (!shape_->sampleMoved(end_.inverse(p), start_.inverse(start), reach, out)) return false;
  out.normal = end_.rotation * out.normal;
  out.point = end_.apply(out.point);
  return true;
}

Vec3 ContactObstacle::surfaceVelocity(const Vec3& surfacePoint) const {
  if (!motion_) return Vec3::Zero();
  const Vec3 body = end_.inverse(surfacePoint);
  return (surfacePoint - start_.apply(body)) / h_;
}

}  // namespace weft
