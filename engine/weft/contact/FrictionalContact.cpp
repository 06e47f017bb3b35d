#include <weft/contact/FrictionalContact.h>

#include <algorithm>
#include <cmath>

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

using ContactKey = std::tuple<int, int, int>;  // node, partner, obstacle

ContactKey keyOf(const ContactPoint& c) {
  return {c.node, c.partner, c.obstacle};
}

// Detection's order: by node, then partner (pairs) or obstacle (obstacle contacts).
bool detectionOrder(const ContactPoint& a, const ContactPoint& b) {
  return keyOf(a) < keyOf(b);
}

// Appends the contacts of `found` that `set` lacks (the same node with the same obstacle or
// partner) and whose constraint the displacement `actual` violates by more than `tolerance` (m):
// it ends the step closer along the contact's normal than the constraint allows
// (ContactPoint.h: n . (x_{n+1} - c) >= skin, i.e. h n . (v - reference) >= 0). A contact the
// step does not violate would be in take-off at its result and change nothing. Returns how many;
// `keys` is scratch; `set` keeps its order, the new ones at its end.
int appendViolated(const std::vector<ContactPoint>& found, const NodeMatrix& actual, double h,
                   double tolerance, std::vector<ContactPoint>& set,
                   std::vector<ContactKey>& keys) {
  keys.clear();
  for (const ContactPoint& c : set) keys.push_back(keyOf(c));
  std::sort(keys.begin(), keys.end());
  const std::size_t old = set.size();
  for (const ContactPoint& c : found) {
    Vec3 d = actual.row(c.node).transpose();
    if (c.partner >= 0) d -= actual.row(c.partner).transpose();
    if (c.normal.dot(d - h * c.reference) >= -tolerance) continue;
    if (!std::binary_search(keys.begin(), keys.end(), keyOf(c))) set.push_back(c);
  }
  return static_cast<int>(set.size() - old);
}

}  // namespace

FrictionalContact::FrictionalContact(
    const Scene& scene, const ClothModel& model,
    const std::vector<std::shared_ptr<const ObstacleShape>>& shapes)
    : model_(model), layering_(model.nodeCount()), solver_(model.nodeCount()) {
  obstacles_.reserve(scene.obstacles.size());
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o)
    obstacles_.emplace_back(scene.obstacles[o], shapes[o]);
  // The margin only decides how early a node joins the contact set (as take-off until it needs
  // a force); a fraction of the edge length covers the motion the prediction misses.
  detector_ =
      std::make_unique<ObstacleContactDetector>(obstacles_, 0.25 * meanEdgeLength(model.rest));
  if (scene.hasSelfCollision())
    selfCollision_ = std::make_unique<SelfCollisionDetector>(scene, model);
}

double FrictionalContact::deepestPenetration(const NodeMatrix& x) const {
  double deepest = 0.0;
  const int m = static_cast<int>(x.rows());
#pragma omp parallel for reduction(max : deepest) schedule(static)
  for (int i = 0; i < m; ++i) {
    const Vec3 p = x.row(i).transpose();
    for (const ContactObstacle& o : obstacles_) {
      SurfaceSample s;
      // A node outside the skin needs no exact distance: reach just past the skin.
      if (o.sample(p, o.thickness(), s)) deepest = std::max(deepest, o.thickness() - s.distance);
    }
  }
  return deepest;
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
  orderPairs();
}

void FrictionalContact::orderPairs() {
  obstacleNodes_.clear();
  for (const ContactPoint& c : obstacleContacts_)
    if (obstacleNodes_.empty() || obstacleNodes_.back() != c.node) obstacleNodes_.push_back(c.node);
  layering_.order(pairs_, obstacleNodes_, layerStart_);
}

int FrictionalContact::addMissedContacts(const NodeMatrix& x, const NodeMatrix& predicted,
                                         const NodeMatrix& actual) {
  // Paths are straight, so no point of a node's path strays further from its predicted path
  // than the end does. A pair's distance then changes by at most twice that, an obstacle
  // distance by at most that; detection took pairs within (1 + kMarginFraction) of their
  // distance and obstacle contacts within the margin, so smaller strays cannot miss a contact.
  const double stray = std::sqrt((actual - predicted).rowwise().squaredNorm().maxCoeff());
  int added = 0;
  if (hasObstacles() && stray >= detector_->margin()) {
    found_.clear();
    detector_->detect(x, actual, h_, found_);
    const int obstacleAdded = appendViolated(
        found_, actual, h_, kViolationTolerance * detector_->margin(), obstacleContacts_, keys_);
    if (obstacleAdded > 0)
      std::sort(obstacleContacts_.begin(), obstacleContacts_.end(), detectionOrder);
    added += obstacleAdded;
  }
  if (hasSelfCollision() &&
      2.0 * stray >= SelfCollisionDetector::kMarginFraction * selfCollision_->smallestDistance()) {
    found_.clear();
    selfCollision_->detect(x, actual, h_, found_);
    const int pairsAdded =
        appendViolated(found_, actual, h_, kViolationTolerance * selfCollision_->smallestDistance(),
                       pairs_, keys_);
    if (pairsAdded > 0)
      std::sort(pairs_.begin(), pairs_.end(), detectionOrder);  // (the layering starts from it)
    added += pairsAdded;
  }
  // New obstacle contacts change which nodes the layering starts from, new pairs the layers.
  if (added > 0 && hasSelfCollision()) orderPairs();
  return added;
}

void FrictionalContact::prepareSolve(const Eigen::VectorXd* lawMass) {
  solver_.setContacts(obstacleContacts_, pairs_, layerStart_, model_.mass, lawMass);
}

int FrictionalContact::solve(const NodeMatrix& freeMomentum, double sweepTolerance) {
  return solver_.solve(freeMomentum, sweepTolerance, kMaxSweeps);
}

}  // namespace weft
