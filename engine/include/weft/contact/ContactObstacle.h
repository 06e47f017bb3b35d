#pragma once
// One obstacle of the scene as contact sees it: its shape in the body frame, its kinematic
// motion (a rigid pose per time, from the scene's optional "motion"), its friction coefficient
// and contact skin. Per step it caches the poses at the start and the end of the step: contacts
// are found against the end-of-step pose (the obstacle is moved before the solve, as in
// DiffCloth) and the surface velocity is the body point's displacement over the step / h.

#include <weft/contact/ObstacleShape.h>
#include <weft/scene/Scene.h>

#include <memory>
#include <optional>

namespace weft {

// A rigid pose: world = rotation * body + translation.
struct RigidPose {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& body) const { return rotation * body + translation; }
  Vec3 inverse(const Vec3& world) const { return rotation.transpose() * (world - translation); }
};

// The pose of a trajectory at time t (HandleTrajectory::target applied to a rigid body).
RigidPose poseAt(const HandleTrajectory& motion, double t);

// The shape the scene's obstacle describes (analytic, or a mesh with its BVH).
std::unique_ptr<ObstacleShape> makeObstacleShape(const Obstacle& obstacle);

class ContactObstacle {
 public:
  // The obstacle with the shape built for it (makeObstacleShape; Model's, shared by the
  // simulator and the backward pass).
  ContactObstacle(const Obstacle& obstacle, std::shared_ptr<const ObstacleShape> shape);

  // Caches the poses at the step's start and end times.
  void beginStep(double t0, double t1);
  // The sample of a world point against the end-of-step pose, in world axes.
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const;
  // The same for a point of a node's path whose start-of-step position was `start` (world): the
  // shape sees the path relative to itself, from `start` in the start-of-step pose to p in the
  // end-of-step pose (ObstacleShape::sampleMoved).
  bool sample(const Vec3& p, const Vec3& start, double reach, SurfaceSample& out) const;
  // Velocity (m/s) over the step of the body point now at world position `surfacePoint`.
  Vec3 surfaceVelocity(const Vec3& surfacePoint) const;

  double friction() const { return friction_; }
  double thickness() const { return thickness_; }
  bool moves() const { return motion_.has_value(); }
  const ObstacleShape& shape() const { return *shape_; }

 private:
  std::shared_ptr<const ObstacleShape> shape_;
  std::optional<HandleTrajectory> motion_;
  double friction_, thickness_;
  RigidPose start_, end_;
  double h_ = 1.0;
};

}  // namespace weft
