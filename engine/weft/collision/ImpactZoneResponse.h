#pragma once
// The impact-zone collision response of a step (Liang et al. 2019 Sec. 3.3-3.4, Algorithm 1 line
// 7): the cloths whose self_collision.model has "impact_zones" form one collision mesh; after the
// dynamics solve, the impacts on the way from the step's start to its end (vertex-face and
// edge-edge CCD) are gathered into zones, and each zone's nodes are moved as little as possible
// in the mass norm (Eqs. 8-9) until the mesh is collision-free: no pair closer than the
// thickness, so no edge through a face. The caller then sets v = (x_end - x_start) / h.

#include <weft/core/Types.h>
#include <weft/model/ClothModel.h>
#include <weft/record/StepStats.h>
#include <weft/scene/Scene.h>

#include <functional>
#include <memory>
#include <vector>

namespace weft::collision {

struct ImpactZoneResult;

// Sees the result of every apply() (the zones, their QPs and solutions; nodes numbered as the
// collision mesh's vertices), before `end` is updated from it. The response keeps no result of
// its own; a benchmark or a test that needs the zones of a run sets one.
using ImpactZoneObserver = std::function<void(const ImpactZoneResult&)>;

class ImpactZoneResponse {
 public:
  ImpactZoneResponse(const Scene& scene, const ClothModel& model);
  ~ImpactZoneResponse();

  // Moves `end` (all nodes of the model, m x 3) so that no impact of the collision mesh remains
  // on the way from `start`; adds the rounds, zones, constraints and QP iterations to `stats`.
  void apply(const NodeMatrix& start, NodeMatrix& end, StepStats& stats) const;

  int nodeCount() const { return static_cast<int>(nodes_.size()); }
  // Global node of each collision-mesh vertex.
  const std::vector<int>& nodes() const { return nodes_; }

  // Replaces the observer (an empty function removes it).
  void setObserver(ImpactZoneObserver observer) { observer_ = std::move(observer); }

 private:
  struct Engine;
  std::vector<int> nodes_;  // global node of each collision-mesh vertex
  std::unique_ptr<Engine> engine_;
  ImpactZoneObserver observer_;
};

}  // namespace weft::collision
