#pragma once
// One contact of one time step, the one record of a contact from detection to the backward pass:
// detection fills which node touches what and the frozen frame of the paper's explicit
// J_n(x_n, v_n) (DiffCloth Eq. 9) with the velocity the law measures against; the contact solve
// completes it with the branch of the Signorini-Coulomb law (Eq. 8), the impulse, the velocity
// and the mass the law held for. The solved record is what the backward pass needs per contact
// (branch, normal and, through d = m u - r, the free momentum the law saw), what the editor draws,
// what contact_branches.npy / contact_forces.npy hold and what stats.csv counts.
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

#include <cstdint>

namespace weft {

// The three branches of DiffCloth Eq. 8. The values are the ids of contact_branches.npy
// (0 = no contact).
enum class ContactBranch : std::uint8_t { None = 0, TakeOff = 1, Stick = 2, Slip = 3 };

const char* branchName(ContactBranch branch);

struct ContactPoint {
  // Found by detection.
  int node = -1;      // global cloth node (the lower index of a pair)
  int partner = -1;   // the other node of a self-collision pair (node < partner), else -1
  int obstacle = -1;  // scene obstacle index of a node-obstacle contact, else -1
  // Contact normal, frozen for the step (the paper's explicit J_n), unit: out of the obstacle,
  // or from `partner` towards `node`. The tangent plane is its orthogonal complement; the law
  // needs no tangent basis.
  Vec3 normal = Vec3::UnitY();
  // The velocity the law measures against (m/s): the surface's tangential velocity less the
  // gap-closing rate, g / h, along the normal (see above).
  Vec3 reference = Vec3::Zero();
  double friction = 0.0;  // Coulomb coefficient of this contact
  // Obstacle contacts: where detection sampled the surface, sample = x_n + pathFraction * (the
  // predicted displacement). The frame (normal, nearest point, surface velocity) is a function of
  // this point, so the backward pass differentiates the frame through it (DiffCloth Sec. 4.3,
  // J_n(x_n, v_n)). A contact added after the solve (FrictionalContact::addMissedContacts)
  // sampled the path actually taken instead; the backward pass still moves its sample with x_n
  // and v_n, which is exact where the frame does not depend on the sample (planes) and an
  // approximation on curved shapes.
  Vec3 sample = Vec3::Zero();
  double pathFraction = 0.0;

  // Completed by the contact solve.
  ContactBranch branch = ContactBranch::None;
  // Contact impulse on `node` (N s; `partner` receives the opposite). The mean contact force
  // over the step is impulse / h; in the paper's notation this is h J_n^T r (Eq. 11).
  Vec3 impulse = Vec3::Zero();
  // The velocity the law holds for (m/s), in world axes: the node's velocity relative to the
  // obstacle surface (or to `partner`) less `reference`. Take-off: normal component > 0; stick:
  // zero; slip: normal component zero and tangential part opposite to the impulse's tangential
  // part.
  Vec3 velocity = Vec3::Zero();
  // Effective mass (kg): the node's lumped mass, or the pair's reduced mass. The free
  // momentum the law saw is effectiveMass * velocity - impulse.
  double effectiveMass = 0.0;
};

}  // namespace weft
