#include "VertexInspector.h"

#include "ClothNodes.h"

namespace weft::editor {

std::optional<VertexReport> inspectVertex(const CachedFrame& frame, int node, double dt,
                                          const std::vector<int>& vertexOffset) {
  if (node < 0 || node >= frame.positions.rows()) return std::nullopt;
  VertexReport r;
  r.node = node;
  r.state = frame.state;
  if (const int cloth = clothOfNode(vertexOffset, node); cloth >= 0) {
    r.cloth = cloth;
    r.localVertex = node - vertexOffset[static_cast<std::size_t>(r.cloth)];
  }
  r.position = frame.positions.row(node).transpose();
  if (frame.velocities.rows() == frame.positions.rows())
    r.velocity = frame.velocities.row(node).transpose();
  if (static_cast<std::size_t>(node) < frame.branches.size())
    r.branch = static_cast<ContactBranch>(frame.branches[static_cast<std::size_t>(node)]);
  for (const ContactPoint& p : frame.contacts.points) {
    if (p.node != node && p.partner != node) continue;
    const double sign = p.node == node ? 1.0 : -1.0;
    VertexContact c;
    c.obstacle = p.obstacle;
    c.partner = p.node == node ? p.partner : p.node;
    c.branch = p.branch;
    c.normal = sign * p.normal;
    c.impulse = sign * p.impulse;
    c.force = dt > 0.0 ? Vec3(c.impulse / dt) : Vec3::Zero();
    c.velocity = sign * p.velocity;
    c.friction = p.friction;
    r.contactImpulse += c.impulse;
    r.contactForce += c.force;
    r.contacts.push_back(c);
  }
  return r;
}

std::vector<Vec3> nodeContactForces(const StepContacts& contacts, int nodes, double dt) {
  std::vector<Vec3> forces(static_cast<std::size_t>(std::max(nodes, 0)), Vec3::Zero());
  if (dt <= 0.0) return forces;
  for (const ContactPoint& p : contacts.points) {
    if (p.node >= 0 && p.node < nodes) forces[static_cast<std::size_t>(p.node)] += p.impulse / dt;
    if (p.partner >= 0 && p.partner < nodes)
      forces[static_cast<std::size_t>(p.partner)] -= p.impulse / dt;
  }
  return forces;
}

}  // namespace weft::editor
