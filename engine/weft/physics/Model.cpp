#include <weft/physics/Model.h>

#include <weft/contact/ContactObstacle.h>
#include <weft/physics/AttachmentConstraint.h>
#include <weft/physics/BendingConstraint.h>
#include <weft/physics/ExternalForce.h>
#include <weft/physics/GravityForce.h>
#include <weft/physics/NodalForces.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/StretchConstraint.h>
#include <weft/physics/WindForce.h>

#include <utility>

namespace weft {

std::shared_ptr<const Model> Model::compile(Scene scene) {
  std::shared_ptr<const Parts> parts = compileParts(scene);
  return std::shared_ptr<const Model>(new Model(std::move(scene), std::move(parts)));
}

std::shared_ptr<const Model> Model::withTimeStep(double dt) const {
  Scene scene = scene_;
  scene.time.dt = dt;
  return std::shared_ptr<const Model>(new Model(std::move(scene), parts_));
}

Model::Model(Scene scene, std::shared_ptr<const Parts> parts)
    : scene_(std::move(scene)), parts_(std::move(parts)) {}

std::shared_ptr<const Model::Parts> Model::compileParts(const Scene& scene) {
  auto parts = std::make_shared<Parts>();
  ClothModel& cloth = parts->cloth;
  cloth = buildClothModel(scene);
  auto addConstraint = [&](std::unique_ptr<ProjectiveConstraint> c) {
    if (c->rowCount() > 0) parts->constraints.push_back(std::move(c));
  };
  addConstraint(std::make_unique<StretchConstraint>(makeStretchConstraint(scene, cloth)));
  addConstraint(std::make_unique<BendingConstraint>(makeBendingConstraint(scene, cloth)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, cloth, false)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene, cloth, true)));

  auto& forces = parts->forces;
  if (scene.gravity) forces.push_back(std::make_unique<GravityForce>(*scene.gravity, cloth.mass));
  if (scene.wind) forces.push_back(std::make_unique<WindForce>(*scene.wind, cloth.lumpedArea));
  bool anyNodalForce = false;
  NodeMatrix nodal = NodeMatrix::Zero(cloth.nodeCount(), 3);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (const PointForce& pf : scene.cloths[c].forces)
      for (int v : pf.vertices) {
        nodal.row(cloth.vertexOffset[c] + v) += pf.force.transpose();
        anyNodalForce = true;
      }
  if (anyNodalForce) forces.push_back(std::make_unique<NodalForces>(std::move(nodal)));

  parts->obstacleShapes.reserve(scene.obstacles.size());
  for (const Obstacle& o : scene.obstacles) parts->obstacleShapes.push_back(makeObstacleShape(o));

  NodeMatrix& velocities = parts->initialVelocities;
  velocities.resize(cloth.nodeCount(), 3);
  for (std::size_t c = 0; c < scene.cloths.size(); ++c)
    for (int i = cloth.vertexOffset[c]; i < cloth.vertexOffset[c + 1]; ++i)
      velocities.row(i) = scene.cloths[c].initialVelocity.transpose();

  // The same order as makeAttachmentConstraint's rows for the handles.
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const auto& attachments = scene.cloths[c].attachments;
    for (std::size_t j = 0; j < attachments.size(); ++j) {
      if (attachments[j].kind != Attachment::Kind::Handle) continue;
      HandleGroup group;
      group.cloth = static_cast<int>(c);
      group.attachment = static_cast<int>(j);
      group.stiffness = attachments[j].stiffness;
      for (int v : attachments[j].vertices) group.nodes.push_back(cloth.vertexOffset[c] + v);
      parts->handles.push_back(std::move(group));
    }
  }
  return parts;
}

Model::Parts::~Parts() = default;
Model::~Model() = default;

std::vector<std::unique_ptr<ProjectiveConstraint>> Model::instantiateConstraints() const {
  std::vector<std::unique_ptr<ProjectiveConstraint>> copies;
  copies.reserve(parts_->constraints.size());
  for (const auto& c : parts_->constraints) copies.push_back(c->clone());
  return copies;
}

}  // namespace weft
