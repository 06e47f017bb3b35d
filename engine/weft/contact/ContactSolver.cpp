#include <weft/contact/ContactSolver.h>

#include <weft/contact/ContactLawJacobian.h>
#include <weft/contact/SignoriniCoulomb.h>

#include <Eigen/QR>

#include <algorithm>

namespace weft {
namespace {

// Below this many independent updates a parallel region costs more than it saves.
constexpr int kParallelMinimum = 512;
// The linearised sweeps of addLawJacobian stop when no contact's impulse changes by more than
// this fraction of the largest free velocity, or at the cap.
constexpr double kLinearTolerance = 1e-12;
constexpr int kLinearSweeps = 1000;

}  // namespace

// A detected contact as the solve starts it: in take-off, no impulse, `recordMass` (the lumped
// mass) for the record and `lawMass` (m~) for the law.
ContactSolver::Contact ContactSolver::started(const ContactPoint& detected, int a, int b,
                                              double lawMass, double recordMass) {
  Contact c;
  c.point = detected;
  c.point.branch = ContactBranch::TakeOff;
  c.point.impulse.setZero();
  c.point.effectiveMass = recordMass;
  c.a = a;
  c.b = b;
  c.lawMass = lawMass;
  c.law.setZero();
  return c;
}

void ContactSolver::setContacts(const std::vector<ContactPoint>& obstacleContacts,
                                const std::vector<ContactPoint>& pairs,
                                const std::vector<int>& layerStart, const Eigen::VectorXd& lumped,
                                const Eigen::VectorXd* lawMass) {
  const Eigen::VectorXd& mass = lawMass ? *lawMass : lumped;
  for (const Slot& s : slots_) slotOf_[s.node] = -1;
  slots_.clear();
  contacts_.clear();
  groupStart_.clear();
  auto slotFor = [&](int node) {
    if (slotOf_[node] < 0) {
      slotOf_[node] = static_cast<int>(slots_.size());
      slots_.push_back(Slot{node, mass[node], Vec3::Zero(), Vec3::Zero(), Mat3::Zero()});
    }
    return slotOf_[node];
  };
  coupled_ = false;
  for (std::size_t k = 0; k < obstacleContacts.size(); ++k) {
    const ContactPoint& c = obstacleContacts[k];
    const bool sameNode = k > 0 && obstacleContacts[k - 1].node == c.node;
    if (!sameNode) groupStart_.push_back(static_cast<int>(contacts_.size()));
    coupled_ = coupled_ || sameNode;
    contacts_.push_back(started(c, slotFor(c.node), -1, mass[c.node], lumped[c.node]));
  }
  groupStart_.push_back(static_cast<int>(contacts_.size()));
  pairBegin_ = static_cast<int>(contacts_.size());
  for (const ContactPoint& c : pairs) {
    const double ma = mass[c.node], mb = mass[c.partner];
    const double la = lumped[c.node], lb = lumped[c.partner];
    contacts_.push_back(
        started(c, slotFor(c.node), slotFor(c.partner), ma * mb / (ma + mb), la * lb / (la + lb)));
  }
  coupled_ = coupled_ || !pairs.empty();
  layerStart_ = layerStart;
}

Vec3 ContactSolver::freeVelocity(const Contact& c) const {
  // Velocity of the contact without its own impulse (the other contacts' impulses included).
  const Slot& a = slots_[c.a];
  Vec3 free = a.freeVelocity + (a.impulse - c.point.impulse) / a.mass;
  if (c.b >= 0) {
    const Slot& b = slots_[c.b];
    free -= b.freeVelocity + (b.impulse + c.point.impulse) / b.mass;
  }
  return free - c.point.reference;
}

double ContactSolver::update(Contact& c) {
  Slot& a = slots_[c.a];
  const Vec3 free = freeVelocity(c);
  Vec3 change;
  // DiffCloth Eq. 8, in the closed form of Ly et al.
  c.point.branch = solveSignoriniCoulomb(c.point.normal, c.point.friction, free, change);
  const Vec3 impulse = c.lawMass * change;
  const Vec3 delta = impulse - c.point.impulse;
  c.point.impulse = impulse;
  a.impulse += delta;
  if (c.b >= 0) slots_[c.b].impulse -= delta;
  return delta.norm() / c.lawMass;
}

int ContactSolver::solve(const NodeMatrix& freeMomentum, double tolerance, int maxSweeps) {
  const int slotCount = static_cast<int>(slots_.size());
#pragma omp parallel for schedule(static) if (slotCount > kParallelMinimum)
  for (int s = 0; s < slotCount; ++s)
    slots_[s].freeVelocity = freeMomentum.row(slots_[s].node).transpose() / slots_[s].mass;

  const int groups = static_cast<int>(groupStart_.size()) - 1;
  int sweeps = 0;
  while (true) {
    double change = 0.0;
    // Obstacle contacts: nodes are independent of each other.
#pragma omp parallel for schedule(static) reduction(max : change) if (groups > kParallelMinimum)
    for (int g = 0; g < groups; ++g)
      for (int k = groupStart_[g]; k < groupStart_[g + 1]; ++k)
        change = std::max(change, update(contacts_[k]));
    // Pairs, layer by layer: within a layer no node appears twice.
    for (std::size_t l = 0; l + 1 < layerStart_.size(); ++l) {
      const int begin = pairBegin_ + layerStart_[l], end = pairBegin_ + layerStart_[l + 1];
#pragma omp parallel for schedule(static) reduction(max \
                                                    : change) if (end - begin > kParallelMinimum)
      for (int k = begin; k < end; ++k) change = std::max(change, update(contacts_[k]));
    }
    ++sweeps;
    lastChange_ = change;
    if (!coupled_ || change <= tolerance || sweeps >= maxSweeps) break;
  }
  return sweeps;
}

void ContactSolver::addImpulses(double scale, NodeMatrix& rhs) const {
  for (const Slot& s : slots_) rhs.row(s.node) += scale * s.impulse.transpose();
}

int ContactSolver::linearize() {
  for (Slot& s : slots_) s.pinned.setZero();
  int changed = 0;
  for (Contact& c : contacts_) {
    changed += c.point.branch != c.linearized;
    c.linearized = c.point.branch;
    c.law = differentiateSignoriniCoulomb(c.point.branch, c.point.normal, c.point.friction,
                                          freeVelocity(c))
                .velocity;
    if (c.b >= 0 || c.point.branch == ContactBranch::TakeOff) continue;
    Mat3& pinned = slots_[c.a].pinned;
    // A second prescribed direction on the node (two obstacles): pin it whole.
    if (c.point.branch == ContactBranch::Stick || !pinned.isZero(0.0))
      pinned.setIdentity();
    else
      pinned = c.point.normal * c.point.normal.transpose();
  }
  // A node on several obstacles: its contacts' linearised impulses solved together. In
  // addLawJacobian's sweeps contact k of the node takes r_k = (m~_k / m) L_k (q + p + sum_{j != k}
  // r_j) (p: the pairs' impulses on the node); contact by contact, that Gauss-Seidel iteration
  // diverges where a slip contact's Jacobian has a large gain, which happens when the branch was
  // decided at another free velocity than the one it is linearised at (an iterate whose sweeps
  // had not settled; docs/how-it-works/contact.md). The block is solved directly instead,
  // R = (I - B)^+ A (q + p), with the
  // minimum-norm solution where the split between the contacts is undetermined (two sticks),
  // as the backward pass picks it (ContactAdjoint).
  const int groups = static_cast<int>(groupStart_.size()) - 1;
  groupResponse_.resize(groups);
  for (int g = 0; g < groups; ++g) {
    const int begin = groupStart_[g], count = groupStart_[g + 1] - begin;
    if (count == 1) {
      groupResponse_[g].resize(0, 0);
      continue;
    }
    Eigen::MatrixXd system = Eigen::MatrixXd::Identity(3 * count, 3 * count), source(3 * count, 3);
    for (int k = 0; k < count; ++k) {
      const Contact& c = contacts_[begin + k];
      const Mat3 a = (c.lawMass / slots_[c.a].mass) * c.law;
      source.middleRows<3>(3 * k) = a;
      for (int j = 0; j < count; ++j)
        if (j != k) system.block<3, 3>(3 * k, 3 * j) = -a;
    }
    groupResponse_[g] =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(system).solve(source);
  }
  return changed;
}

void ContactSolver::addLawJacobian(const NodeMatrix& q, NodeMatrix& out) const {
  // r_c = m_eff du(w), w = f_a / m_a (- f_b / m_b) - reference (DiffCloth Eq. 12's per-node law).
  const int groups = static_cast<int>(groupStart_.size()) - 1;
  if (!coupled_) {
    // One contact per node: each impulse depends on its own node's momentum only.
#pragma omp parallel for schedule(static) if (groups > kParallelMinimum)
    for (int g = 0; g < groups; ++g) {
      const Contact& c = contacts_[groupStart_[g]];
      const int node = slots_[c.a].node;
      out.row(node) += (c.law * q.row(node).transpose()).transpose();
    }
    return;
  }
  // Coupled contacts (a node on two obstacles, pairs sharing nodes with each other or with
  // obstacle contacts): the sweeps of solve() converge to a fixed point whose derivative is the
  // fixed point of the same sweeps linearised in each contact's branch, r_c = m_eff J_c w_c with
  // w_c built from the other contacts' linearised impulses. Run in solve()'s order until they
  // stop changing. Where the fixed point leaves a split undetermined (two sticks on one node),
  // the sweeps still settle on one split with the determined total.
  const int contactCount = static_cast<int>(contacts_.size());
  linearImpulse_.assign(contactCount, Vec3::Zero());
  linearTotal_.assign(slots_.size(), Vec3::Zero());
  double scale = 0.0;
  for (const Slot& s : slots_) scale = std::max(scale, q.row(s.node).norm() / s.mass);
  if (scale == 0.0) return;
  auto update = [&](int k) {
    const Contact& c = contacts_[k];
    const Slot& a = slots_[c.a];
    Vec3 w = (q.row(a.node).transpose() + linearTotal_[c.a] - linearImpulse_[k]) / a.mass;
    if (c.b >= 0) {
      const Slot& b = slots_[c.b];
      w -= (q.row(b.node).transpose() + linearTotal_[c.b] + linearImpulse_[k]) / b.mass;
    }
    const Vec3 impulse = c.lawMass * (c.law * w);
    const Vec3 delta = impulse - linearImpulse_[k];
    linearImpulse_[k] = impulse;
    linearTotal_[c.a] += delta;
    if (c.b >= 0) linearTotal_[c.b] -= delta;
    return delta.norm() / c.lawMass;
  };
  // A node's obstacle contacts together (linearize()): R = groupResponse_ (q + p).
  auto updateGroup = [&](int g) {
    const int begin = groupStart_[g], count = groupStart_[g + 1] - begin;
    const int slot = contacts_[begin].a;
    Vec3 base = q.row(slots_[slot].node).transpose() + linearTotal_[slot];
    for (int k = begin; k < begin + count; ++k) base -= linearImpulse_[k];
    double change = 0.0;
    for (int k = 0; k < count; ++k) {
      const Contact& c = contacts_[begin + k];
      const Vec3 impulse = groupResponse_[g].middleRows<3>(3 * k) * base;
      const Vec3 delta = impulse - linearImpulse_[begin + k];
      linearImpulse_[begin + k] = impulse;
      linearTotal_[slot] += delta;
      change = std::max(change, delta.norm() / c.lawMass);
    }
    return change;
  };
  for (int sweep = 0; sweep < kLinearSweeps; ++sweep) {
    double change = 0.0;
#pragma omp parallel for schedule(static) reduction(max : change) if (groups > kParallelMinimum)
    for (int g = 0; g < groups; ++g)
      change = std::max(change, groupStart_[g + 1] - groupStart_[g] == 1 ? update(groupStart_[g])
                                                                         : updateGroup(g));
    for (std::size_t l = 0; l + 1 < layerStart_.size(); ++l) {
      const int begin = pairBegin_ + layerStart_[l], end = pairBegin_ + layerStart_[l + 1];
#pragma omp parallel for schedule(static) reduction(max \
                                                    : change) if (end - begin > kParallelMinimum)
      for (int k = begin; k < end; ++k) change = std::max(change, update(k));
    }
    if (change <= kLinearTolerance * scale) break;
  }
  for (std::size_t s = 0; s < slots_.size(); ++s)
    out.row(slots_[s].node) += linearTotal_[s].transpose();
}

void ContactSolver::pinnedVelocity(const NodeMatrix& r, NodeMatrix& z) const {
  for (const Slot& s : slots_)
    z.row(s.node) = (s.pinned * r.row(s.node).transpose()).transpose() / s.mass;
}

void ContactSolver::removePinned(NodeMatrix& v) const {
  for (const Slot& s : slots_) v.row(s.node) -= (s.pinned * v.row(s.node).transpose()).transpose();
}

ContactBranch ContactSolver::branchOfNode(int node) const {
  const int slot = node >= 0 && node < static_cast<int>(slotOf_.size()) ? slotOf_[node] : -1;
  if (slot >= 0)
    for (const Contact& c : contacts_)
      if (c.a == slot || c.b == slot) return c.point.branch;
  return ContactBranch::None;
}

void ContactSolver::record(StepContacts& out) const {
  out.points.clear();
  out.points.reserve(contacts_.size());
  for (const Contact& c : contacts_) {
    ContactPoint p = c.point;
    // The velocity with all impulses applied, the one Eq. 8 is checked against.
    const Slot& a = slots_[c.a];
    Vec3 u = a.freeVelocity + a.impulse / a.mass;
    if (c.b >= 0) u -= slots_[c.b].freeVelocity + slots_[c.b].impulse / slots_[c.b].mass;
    p.velocity = u - c.point.reference;
    out.points.push_back(p);
  }
  out.sweepChange = lastChange_;
  out.pairLayers = static_cast<int>(layerStart_.size()) - 1;
}

}  // namespace weft
