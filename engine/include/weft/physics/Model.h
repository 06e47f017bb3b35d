#pragma once
// A scene compiled for simulation, once: the cloths as one nodal system, the projective
// constraint families (DiffCloth Eq. 4), the external forces, the obstacles' shapes, the time
// step and which modules the scene calls for. Immutable once compiled and shared
// (std::shared_ptr<const Model>) by the forward simulator, the backward pass (DiffCloth Sec. 4:
// P and Delta P come from the same families) and the Trajectory they hand each other, so nothing
// downstream reads the scene's files or rebuilds its parts again.
//
// What changes during a run stays out of the model: each solver works on its own instances of
// the constraint families (instantiateConstraints: the projections' derivatives and the handles'
// targets are per step) and poses the shared obstacle shapes itself (ContactObstacle).

#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/scene/Scene.h>

#include <memory>
#include <vector>

namespace weft {

// The engine's internals a model holds (private headers of the engine).
class ExternalForce;
class ObstacleShape;
class ProjectiveConstraint;

// A handle (an attachment of kind "handle"): its nodes, in the order of the handles
// constraint's rows, which take the handles in scene order (cloth, then attachment).
struct HandleGroup {
  int cloth = 0;
  int attachment = 0;      // index in the cloth's attachments
  std::vector<int> nodes;  // global node indices
  double stiffness = 0.0;  // per node (PD attachment weight)
};

class Model {
 public:
  // Compiles `scene` (a validated scene from the scene loader; the model keeps its own copy).
  // Throws InputError for an obstacle mesh without triangles.
  static std::shared_ptr<const Model> compile(Scene scene);
  // This model at another time step (adaptive time stepping's finer levels): every compiled part
  // is shared, nothing is rebuilt; only the scene's time.dt differs.
  std::shared_ptr<const Model> withTimeStep(double dt) const;
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  const Scene& scene() const { return scene_; }
  const ClothModel& cloth() const { return parts_->cloth; }
  int nodeCount() const { return parts_->cloth.nodeCount(); }
  double dt() const { return scene_.time.dt; }
  int stepCount() const { return scene_.time.steps; }
  const SolverSettings& solver() const { return scene_.solver; }

  // The constraint families with at least one row, in the order stretch, bending, attachments,
  // handles: the order of P's terms and of the module report.
  const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints() const {
    return parts_->constraints;
  }
  // Working copies of constraints() for one solver (same data, own per-step state).
  std::vector<std::unique_ptr<ProjectiveConstraint>> instantiateConstraints() const;
  // The external forces the scene names (gravity, wind, forces on nodes), in that order.
  const std::vector<std::unique_ptr<ExternalForce>>& forces() const { return parts_->forces; }
  // One shape per scene obstacle, in scene order (a mesh obstacle's BVH is built here).
  const std::vector<std::shared_ptr<const ObstacleShape>>& obstacleShapes() const {
    return parts_->obstacleShapes;
  }
  // Obstacles or self-collision: the scene needs the contact modules.
  bool hasContact() const { return !scene_.obstacles.empty() || scene_.hasSelfCollision(); }
  // Every node's velocity at t = 0 (its cloth's initial_velocity).
  const NodeMatrix& initialVelocities() const { return parts_->initialVelocities; }
  // The scene's handles in scene order (empty without handles).
  const std::vector<HandleGroup>& handles() const { return parts_->handles; }

 private:
  // What the scene compiles to, independent of its time step.
  struct Parts {
    ClothModel cloth;
    std::vector<std::unique_ptr<ProjectiveConstraint>> constraints;
    std::vector<std::unique_ptr<ExternalForce>> forces;
    std::vector<std::shared_ptr<const ObstacleShape>> obstacleShapes;
    NodeMatrix initialVelocities;
    std::vector<HandleGroup> handles;
    ~Parts();
  };
  Model(Scene scene, std::shared_ptr<const Parts> parts);
  static std::shared_ptr<const Parts> compileParts(const Scene& scene);

  Scene scene_;
  std::shared_ptr<const Parts> parts_;
};

}  // namespace weft
