#pragma once
// What detection hands to the solver for one contact of one step: the frozen frame of the
// paper's explicit J_n(x_n, v_n) (DiffCloth Eq. 9) and the velocity the law measures against.
//
// Gap-aware velocity constraint. DiffCloth Eq. 8 constrains the end-of-step normal velocity,
// u_N >= 0, for every node found within a margin of an obstacle; a node detected while still
// some distance g above the surface would then stop short of it, and one found slightly inside
// would stay inside. Weft constrains instead the end-of-step position along the frozen normal,
//   n . (x_{n+1} - c) >= skin  <=>  n . v_{n+1} >= -(g / h),  g = n . (x_n - c) - skin,
// where c is the nearest surface point (end-of-step obstacle pose). This is Eq. 8 for the
// shifted velocity u = v_{n+1} - reference, reference = (obstacle surface velocity, tangential
// part) - (g / h) n: take-off, stick and slip keep their meaning (stick: the node moves with the
// surface and lands on it), the law stays the per-node closed form of Ly et al., and a node
// resting on the surface (g = 0) sees exactly the paper's u_N >= 0. Self-collision pairs use the
// same form with u = v_a - v_b and g = |x_a - x_b| - radius.

#include <weft/core/Types.h>

namespace weft {

struct ContactConstraint {
  int node = -1;                  // the node (the lower index of a pair)
  int partner = -1;               // the pair's other node, or -1
  int obstacle = -1;              // the obstacle, or -1
  Vec3 normal = Vec3::UnitY();    // unit: out of the obstacle, or from partner to node
  Vec3 reference = Vec3::Zero();  // m/s, see above
  double friction = 0.0;
  // Obstacle contacts: where detection sampled the surface, sample = x_n + pathFraction * (the
  // predicted displacement). The frame (normal, nearest point, surface velocity) is a function of
  // this point, so the backward pass differentiates the frame through it (DiffCloth Sec. 4.3,
  // J_n(x_n, v_n)). A contact added after the solve (FrictionalContact::addMissedContacts)
  // sampled the path actually taken instead; the backward pass still moves its sample with x_n
  // and v_n, which is exact where the frame does not depend on the sample (planes) and an
  // approximation on curved shapes.
  Vec3 sample = Vec3::Zero();
  double pathFraction = 0.0;
};

}  // namespace weft
