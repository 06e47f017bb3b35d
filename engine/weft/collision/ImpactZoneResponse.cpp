#include <weft/collision/ImpactZoneResponse.h>

#include <weft/collision/CollisionMesh.h>
#include <weft/collision/ImpactZones.h>
#include <weft/collision/SweptBroadPhase.h>

#include <algorithm>

namespace weft::collision {

namespace {

// The QP keeps each pair this much farther apart than detection looks: a pair the response put
// exactly at the thickness is not found again by rounding alone (ARCSim likewise detects at a
// smaller thickness than it projects to).
constexpr double kProjectionMargin = 1.1;

double thicknessOf(const Scene& scene) {
  // One collision mesh, one thickness: the largest the cloths ask for.
  double thickness = 0.0;
  for (const Cloth& c : scene.cloths)
    if (c.selfCollision && c.selfCollision->impactZones)
      thickness = std::max(thickness, c.selfCollision->thickness);
  return thickness;
}

}  // namespace

struct ImpactZoneResponse::Engine {
  CollisionMesh mesh;
  double thickness;
  SweptBroadPhase broadPhase;
  ImpactZones zones;
  NodeMatrix start, end;

  Engine(CollisionMesh m, double delta)
      : mesh(std::move(m)), thickness(delta), broadPhase(mesh.mesh), zones([&] {
          ImpactZoneOptions o;
          o.thickness = kProjectionMargin * delta;
          return o;
        }()) {}
};

ImpactZoneResponse::ImpactZoneResponse(const Scene& scene, const ClothModel& model) {
  CollisionMesh mesh = CollisionMesh::of(scene, model, true);
  nodes_ = mesh.nodes;
  engine_ = std::make_unique<Engine>(std::move(mesh), thicknessOf(scene));
}

ImpactZoneResponse::~ImpactZoneResponse() = default;

void ImpactZoneResponse::apply(const NodeMatrix& start, NodeMatrix& end, StepStats& stats) const {
  Engine& e = *engine_;
  e.mesh.gather(start, e.start);
  e.mesh.gather(end, e.end);
  const ImpactDetector detect = [&e](const NodeMatrix& a, const NodeMatrix& b) {
    return e.broadPhase.findImpacts(a, b, e.thickness);
  };
  const ImpactZoneResult result = e.zones.apply(e.start, e.end, e.mesh.mass, detect);
  if (observer_) observer_(result);
  const ImpactZoneStats& s = result.stats;
  stats.impactRounds += s.rounds;
  stats.impactZones += s.zones;
  stats.impactConstraints += s.constraints;
  stats.impactQpIterations += static_cast<int>(s.qpIterationsTotal);
  stats.impactRigidZones += s.rigidZones;
  stats.impactsResolved = stats.impactsResolved && s.converged;
  stats.impactMove = std::max(
      stats.impactMove, std::sqrt((result.positions - e.end).rowwise().squaredNorm().maxCoeff()));
  e.mesh.scatter(result.positions, end);
}

}  // namespace weft::collision
