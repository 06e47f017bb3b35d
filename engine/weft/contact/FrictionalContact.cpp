#include <weft/contact/FrictionalContact.h>

namespace weft {
namespace {

double meanEdgeLength(const TriangleMesh& mesh) {
  double sum = 0.0;
  int count = 0;
  for (const MeshEdge& e : buildEdges(mesh)) {
    sum += (mesh.vertices.row(e.a) - mesh.vertices.row(e.b)).norm();
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace

FrictionalContact::FrictionalContact(const Scene& scene, const ClothModel& model)
    : model_(model), layering_(model.nodeCount()), solver_(model.nodeCount()) {
  obstacles_.reserve(scene.obstacles.size());
  for (const Obstacle& o : scene.obstacles) obstacles_.emplace_back(o);
  // The margin only decides how early a node joins the contact set (as take-off until it needs
  // a force); a fraction of the edge length covers the motion the prediction misses.
  detector_ = std::make_unique<ObstacleContactDetector>(obstacles_, 0.25 * meanEdgeLength(model.rest));
  if (scene.hasSelfCollision()) selfCollision_ = std::make_unique<SelfCollisionDetector>(scene, model);
}

void FrictionalContact::beginStep(double t0, double t1) {
  h_ = t1 - t0;
  for (ContactObstacle& o : obstacles_) o.beginStep(t0, t1);
  obstacleContacts_.clear();
  pairs_.clear();
  layerStart_.assign(1, 0);
}

void FrictionalContact::detectObstacles(const NodeMatrix& x, const NodeMatrix& displacement) {
  detector_->detect(x, displacement, h_, obstacleContacts_);
}

void FrictionalContact::detectSelfCollisions(const NodeMatrix& x, const NodeMatrix& displacement) {
  selfCollision_->detect(x, displacement, h_, pairs_);
  obstacleNodes_.clear();
  for (const ContactConstraint& c : obstacleContacts_)
    if (obstacleNodes_.empty() || obstacleNodes_.back() != c.node) obstacleNodes_.push_back(c.node);
  layering_.order(pairs_, obstacleNodes_, layerStart_);
}

void FrictionalContact::prepareSolve(const Eigen::VectorXd* lawMass) {
  solver_.setContacts(obstacleContacts_, pairs_, layerStart_, model_.mass, lawMass);
}

int FrictionalContact::solve(const NodeMatrix& freeMomentum, double sweepTolerance) {
  return solver_.solve(freeMomentum, sweepTolerance, kMaxSweeps);
}

}  // namespace weft
