#pragma once
// The adapter between the engine and the renderer: turns a Scene and a cloth state into the
// renderer's plain frame description (cloth mesh, obstacles, attachment markers, handle
// trajectories, target ghosts). The renderer never sees a Scene; the engine never sees GL.

#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/render/RenderScene.h>
#include <weft/scene/Scene.h>

#include <optional>
#include <string>
#include <vector>

namespace weft {

render::ObstacleShape toRenderShape(const Obstacle& obstacle);
// The shape of a moving obstacle at time t (its "motion" is rigid: a rotation, then a translation).
render::ObstacleShape movedShape(const render::ObstacleShape& shape, const HandleTrajectory& motion,
                                 double t);
render::PointMatrix toRenderPoints(const NodeMatrix& positions);

class FrameBuilder {
 public:
  // Reads the task's targets (trajectory or final) when their files exist; a target that
  // cannot be shown adds a line to `warnings` instead of failing the render.
  FrameBuilder(const Scene& scene, const ClothModel& model,
               std::vector<std::string>* warnings = nullptr);

  // The frame of state `state` (time state * dt) with cloth positions `x` (nodes x 3).
  render::RenderScene frame(const NodeMatrix& x, int state) const;

 private:
  render::RenderScene static_;                            // obstacles at rest and handle curves
  std::vector<std::optional<HandleTrajectory>> motions_;  // per obstacle
  double dt_ = 0.0;
  render::TriangleList triangles_;
  std::vector<int> fixed_, handles_;      // global node indices
  std::vector<int> fixedGroups_;          // per fixed_ entry: its pin group
  std::vector<NodeMatrix> targetStates_;  // trajectory target: one full state per step
  NodeMatrix finalTarget_;                // final target rows, aligned with finalVertices_
  std::vector<int> finalVertices_;        // empty with a full-mesh final target
};

}  // namespace weft
