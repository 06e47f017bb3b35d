#pragma once
// Handle targets near obstacles: the one walk over (handle vertex, obstacle, step) that the scene
// check for handles entering obstacles (HandleObstacleCheck.h) and the clearance loss
// (diff/HandleClearanceLoss.h) both make.

#include <weft/core/Types.h>
#include <weft/scene/Scene.h>

#include <functional>

namespace weft {

struct HandleTargetSample {
  int cloth = 0, attachment = 0, obstacle = 0;
  double time = 0.0;      // t_n = n * time.dt
  double distance = 0.0;  // signed distance of the target to the obstacle's surface (< 0 inside)
  Vec3 normal = Vec3::UnitY();  // the surface's outward normal there, in the world frame
  const char* shape = "";       // the obstacle shape's name (a string literal)
};

// Whether the scene has anything to sample: a handle attachment and an obstacle.
bool hasHandlesAndObstacles(const Scene& scene);

// Calls visit for every handle vertex's target at t_n = n * time.dt, n = firstStep..time.steps,
// that lies closer than `reach` to an obstacle's surface (distance < reach; a moving obstacle at
// its pose at t_n), in the order cloth, attachment, obstacle, step, vertex. The obstacles' shapes
// are built only when hasHandlesAndObstacles(scene).
void forEachHandleTargetNearObstacle(const Scene& scene, int firstStep, double reach,
                                     const std::function<void(const HandleTargetSample&)>& visit);

}  // namespace weft
