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
  return std::shared_ptr<const Model>(new Model(std::move(scene)));
}

Model::Model(Scene scene) : scene_(std::move(scene)), cloth_(buildClothModel(scene_)) {
  auto addConstraint = [this](std::unique_ptr<ProjectiveConstraint> c) {
    if (c->rowCount() > 0) constraints_.push_back(std::move(c));
  };
  addConstraint(std::make_unique<StretchConstraint>(makeStretchConstraint(scene_, cloth_)));
  addConstraint(std::make_unique<BendingConstraint>(makeBendingConstraint(scene_, cloth_)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene_, cloth_, false)));
  addConstraint(
      std::make_unique<AttachmentConstraint>(makeAttachmentConstraint(scene_, cloth_, true)));

  if (scene_.gravity)
    forces_.push_back(std::make_unique<GravityForce>(*scene_.gravity, cloth_.mass));
  if (scene_.wind) forces_.push_back(std::make_unique<WindForce>(*scene_.wind, cloth_.lumpedArea));
  bool anyNodalForce = false;
  NodeMatrix nodal = NodeMatrix::Zero(cloth_.nodeCount(), 3);
  for (std::size_t c = 0; c < scene_.cloths.size(); ++c)
    for (const PointForce& pf : scene_.cloths[c].forces)
      for (int v : pf.vertices) {
        nodal.row(cloth_.vertexOffset[c] + v) += pf.force.transpose();
        anyNodalForce = true;
      }
  if (anyNodalForce) forces_.push_back(std::make_unique<NodalForces>(std::move(nodal)));

  obstacleShapes_.reserve(scene_.obstacles.size());
  for (const Obstacle& o : scene_.obstacles) obstacleShapes_.push_back(makeObstacleShape(o));

  initialVelocities_.resize(cloth_.nodeCount(), 3);
  for (std::size_t c = 0; c < scene_.cloths.size(); ++c)
    for (int i = cloth_.vertexOffset[c]; i < cloth_.vertexOffset[c + 1]; ++i)
      initialVelocities_.row(i) = scene_.cloths[c].initialVelocity.transpose();
}

Model::~Model() = default;

std::vector<std::unique_ptr<ProjectiveConstraint>> Model::instantiateConstraints() const {
  std::vector<std::unique_ptr<ProjectiveConstraint>> copies;
  copies.reserve(constraints_.size());
  for (const auto& c : constraints_) copies.push_back(c->clone());
  return copies;
}

}  // namespace weft
