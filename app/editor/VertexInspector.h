#pragma once
// What the vertex inspector shows for one cloth vertex at one cached state: position, velocity
// and every contact of the step that produced the state (branch, what it touches, normal,
// impulse and mean force), read straight from the frame the simulation cache recorded. Also
// the per-node contact forces the viewport draws as arrows. No window: unit tested against the
// simulator's own trajectory.

#include "SimulationCache.h"

#include <weft/core/Types.h>
#include <weft/record/ContactPoint.h>

#include <optional>
#include <vector>

namespace weft::editor {

// One contact as seen from the inspected vertex: for the second node of a self-collision pair
// the normal, impulse, force and velocity are turned around (it receives the opposite impulse).
struct VertexContact {
  int obstacle = -1;  // scene obstacle index, or -1
  int partner = -1;   // the other node of a self-collision pair, or -1
  ContactBranch branch = ContactBranch::None;
  Vec3 normal = Vec3::Zero();
  Vec3 impulse = Vec3::Zero();   // N s, on this vertex
  Vec3 force = Vec3::Zero();     // N, impulse / dt: the mean force over the step
  Vec3 velocity = Vec3::Zero();  // m/s, relative to the obstacle surface or the partner
  double friction = 0.0;
};

struct VertexReport {
  int node = -1, state = 0;
  int cloth = -1, localVertex = -1;  // which cloth, and the vertex's index in its mesh
  Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();
  // The branch the viewport colours the vertex with (CachedFrame::branches), None without contact.
  ContactBranch branch = ContactBranch::None;
  Vec3 contactImpulse = Vec3::Zero(), contactForce = Vec3::Zero();  // sums over `contacts`
  std::vector<VertexContact> contacts;
};

// The report of `node` in `frame`; nullopt when the node is not in the frame. `dt` turns
// impulses into forces; `vertexOffset` (ClothModel::vertexOffset) names the cloth.
std::optional<VertexReport> inspectVertex(const CachedFrame& frame, int node, double dt,
                                          const std::vector<int>& vertexOffset);

// The total contact force on every node (N), as `weft simulate` writes contact_forces.npy:
// impulse / dt, the opposite for the partner of a pair.
std::vector<Vec3> nodeContactForces(const StepContacts& contacts, int nodes, double dt);

}  // namespace weft::editor
