#pragma once
// One contact of one time step as the solver leaves it: which node touches what, in which
// branch of the Signorini-Coulomb law (DiffCloth Eq. 8), in which frame, with which impulse and
// velocity. This is what the backward pass needs per contact (branch, normal and, through
// d = m u - r, the free momentum the law saw), what the editor draws and what stats.csv counts.

#include <weft/core/Types.h>

#include <cstdint>

namespace weft {

// The three branches of DiffCloth Eq. 8. The values are the ids of contact_branches.npy
// (0 = no contact).
enum class ContactBranch : std::uint8_t { None = 0, TakeOff = 1, Stick = 2, Slip = 3 };

const char* branchName(ContactBranch branch);

struct ContactPoint {
  int node = -1;      // global cloth node
  int partner = -1;   // the other node of a self-collision pair (node < partner), else -1
  int obstacle = -1;  // scene obstacle index of a node-obstacle contact, else -1
  ContactBranch branch = ContactBranch::None;
  // Contact normal, frozen for the step (the paper's explicit J_n): out of the obstacle, or
  // from `partner` towards `node`. The tangent plane is its orthogonal complement; the law needs
  // no tangent basis.
  Vec3 normal = Vec3::Zero();
  // Contact impulse on `node` (N s; `partner` receives the opposite). The mean contact force
  // over the step is impulse / h; in the paper's notation this is h J_n^T r (Eq. 11).
  Vec3 impulse = Vec3::Zero();
  // The velocity the law holds for (m/s), in world axes: the node's velocity relative to the
  // obstacle surface (or to `partner`), plus the gap-closing rate along the normal (see
  // FrictionalContact.h). Take-off: normal component > 0; stick: zero; slip: normal component
  // zero and tangential part opposite to the impulse's tangential part.
  Vec3 velocity = Vec3::Zero();
  // Coulomb coefficient of this contact.
  double friction = 0.0;
  // Effective mass (kg): the node's lumped mass, or the pair's reduced mass. The free
  // momentum the law saw is effectiveMass * velocity - impulse.
  double effectiveMass = 0.0;
  // The velocity the law measures against (ContactConstraint.h): the surface's tangential
  // velocity less the gap-closing rate, gap / h, along the normal.
  Vec3 reference = Vec3::Zero();
  // Obstacle contacts: the point where detection sampled the surface and its fraction of the
  // predicted path (ContactConstraint.h); what the frame is a function of, for the backward pass.
  Vec3 sample = Vec3::Zero();
  double pathFraction = 0.0;
};

}  // namespace weft
