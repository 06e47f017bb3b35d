#pragma once
// Node-node self-collision detection (DiffCloth; notes Sec. 2.4), built only for scenes whose
// cloths ask for it. Two nodes of self-colliding cloths collide when their predicted paths over
// the step come closer than the collision distance (plus a margin): the minimum over
// tau in [0, 1] of |dx + tau dd| for the relative position dx and relative displacement dd.
// Pairs that share a triangle are never tested, nor mesh neighbours that start within the
// collision distance (plus the margin) in the rest mesh: nodes of the same cloth joined by a path
// of rest edges no longer than kPathFactor times that distance. Such nodes are held apart by the
// cloth's own stretching; a contact between them would fight it from the first step. Nodes of
// different cloths, and nodes of one cloth far apart along its mesh (two layers of a cloth laid
// folded), are never excluded however close they start: they are separate layers, and excluding
// them by their rest distance alone would let them pass through each other. The frame comes from
// the pair's relative position at the start of the step, n = (x_a - x_b)/|x_a - x_b|, a < b
// (ContactPoint.h).
//
// Broad phase: each node's swept box in a SpatialHashGrid, so the cost grows linearly with
// the node count.

#include <weft/contact/ParallelContactCollector.h>
#include <weft/contact/SpatialHashGrid.h>
#include <weft/model/ClothModel.h>
#include <weft/record/ContactPoint.h>

#include <vector>

namespace weft {

class SelfCollisionDetector {
 public:
  SelfCollisionDetector(const Scene& scene, const ClothModel& model);

  // Appends the step's pairs, sorted by (a, b) so that the result does not depend on the
  // thread count.
  void detect(const NodeMatrix& x, const NodeMatrix& displacement, double h,
              std::vector<ContactPoint>& out);

  // The scene's `radius` is the collision distance: node pairs are kept at least this far apart.
  double collisionDistance(int a, int b) const { return 0.5 * (distance_[a] + distance_[b]); }
  bool collides(int node) const { return distance_[node] > 0.0; }
  double smallestDistance() const { return smallestDistance_; }  // over the colliding nodes
  // Shares a triangle, or is a mesh neighbour (same cloth, rest path <= kPathFactor times the
  // reach) that starts within the reach (1 + kMarginFraction) * collisionDistance(a, b).
  bool excluded(int a, int b) const;
  // Detection margin: pairs are taken into the contact set this much before they touch.
  static constexpr double kMarginFraction = 0.5;  // of the collision distance
  // How much longer than their straight rest distance a path of rest edges between two mesh
  // neighbours may be: 2 covers the detours of a regular grid (at most sqrt 2, across the
  // diagonals its triangles do not have) and of reasonably shaped triangles.
  static constexpr double kPathFactor = 2.0;
  static constexpr double kCellOverBoxSize = 2.0;  // broad-phase cell size, in typical swept boxes
  int lastCandidateCount() const { return lastCandidates_; }

 private:
  std::vector<double>
      distance_;  // per node: the cloth's radius, 0 for cloths without self-collision
  std::vector<double> friction_;  // per node: the cloth's self-collision friction
  std::vector<int> excludedStart_,
      excluded_;            // per node, the partners excluded() names (CSR, sorted)
  std::vector<int> nodes_;  // the nodes that collide
  SpatialHashGrid grid_;
  std::vector<Vec3> lower_, upper_;
  std::vector<std::pair<int, int>> candidates_;
  ParallelContactCollector collector_;
  int lastCandidates_ = 0;
  double smallestDistance_ = 0.0;
};

}  // namespace weft
