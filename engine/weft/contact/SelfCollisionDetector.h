#pragma once
// Node-node self-collision detection (DiffCloth; notes Sec. 2.4), built only for scenes whose
// cloths ask for it. Two nodes of self-colliding cloths collide when their predicted paths over
// the step come closer than the collision distance (plus a margin): the minimum over
// tau in [0, 1] of |dx + tau dd| for the relative position dx and relative displacement dd.
// Pairs that share a triangle are never tested, nor pairs closer than the collision distance in
// the rest mesh (they would start in contact). The frame comes from the pair's relative
// position at the start of the step, n = (x_a - x_b)/|x_a - x_b|, a < b (ContactConstraint.h).
//
// Broad phase: each node's swept box in a SpatialHashGrid, so the cost grows linearly with
// the node count.

#include <weft/contact/ContactConstraint.h>
#include <weft/contact/ParallelContactCollector.h>
#include <weft/contact/SpatialHashGrid.h>
#include <weft/physics/ClothModel.h>

#include <vector>

namespace weft {

class SelfCollisionDetector {
 public:
  SelfCollisionDetector(const Scene& scene, const ClothModel& model);

  // Appends the step's pairs, sorted by (a, b) so that the result does not depend on the
  // thread count.
  void detect(const NodeMatrix& x, const NodeMatrix& displacement, double h, std::vector<ContactConstraint>& out);

  // The scene's `radius` is the collision distance: node pairs are kept at least this far apart.
  double collisionDistance(int a, int b) const { return 0.5 * (distance_[a] + distance_[b]); }
  bool collides(int node) const { return distance_[node] > 0.0; }
  bool excluded(int a, int b) const;  // shares a triangle, or starts within the collision distance
  // Detection margin: pairs are taken into the contact set this much before they touch.
  static constexpr double kMarginFraction = 0.5;  // of the collision distance
  int lastCandidateCount() const { return lastCandidates_; }

 private:
  const ClothModel& model_;
  std::vector<double> distance_;   // per node: the cloth's radius, 0 for cloths without self-collision
  std::vector<double> friction_;   // per node: the cloth's self-collision friction
  std::vector<int> neighbourStart_, neighbours_;  // nodes sharing a triangle (CSR, sorted)
  std::vector<int> nodes_;                        // the nodes that collide
  SpatialHashGrid grid_;
  std::vector<Vec3> lower_, upper_;
  std::vector<std::pair<int, int>> candidates_;
  ParallelContactCollector collector_;
  int lastCandidates_ = 0;
};

}  // namespace weft
