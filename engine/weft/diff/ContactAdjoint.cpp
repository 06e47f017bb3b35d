#include <weft/diff/ContactAdjoint.h>

#include <weft/contact/ContactLawJacobian.h>
#include <weft/core/Error.h>

#include <Eigen/SVD>

#include <cmath>
#include <limits>
#include <string>

namespace weft {
namespace {

// Central-difference step for the shape's frame (m). The frame varies on the scale of the
// shape's curvature radius (centimetres and up): at 1e-6 m the truncation error (eps^2 / R^2)
// and the round-off (1e-16 / eps) are both below 1e-9 of the derivative.
constexpr double kFrameStep = 1e-6;
constexpr double kAnyReach = std::numeric_limits<double>::max();

// The groups of contacts coupled through shared nodes (the connected components of T's
// off-diagonal blocks), each with two or more contacts. `sharing`: node -> (contact, sign).
std::vector<std::vector<int>> coupledGroups(
    const std::vector<std::vector<std::pair<int, double>>>& sharing, int count) {
  std::vector<int> parent(count);
  for (int k = 0; k < count; ++k) parent[k] = k;
  const auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const auto& list : sharing)
    for (std::size_t i = 1; i < list.size(); ++i) parent[root(list[i].first)] = root(list[0].first);
  std::vector<std::vector<int>> byRoot(count);
  for (int k = 0; k < count; ++k) byRoot[root(k)].push_back(k);
  std::vector<std::vector<int>> groups;
  for (std::vector<int>& g : byRoot)
    if (g.size() > 1) groups.push_back(std::move(g));
  return groups;
}

}  // namespace

ContactAdjoint::ContactAdjoint(const Model& model)
    : scene_(model.scene()), model_(model.cloth()), h_(model.dt()) {
  obstacles_.reserve(scene_.obstacles.size());
  for (std::size_t o = 0; o < scene_.obstacles.size(); ++o)
    obstacles_.emplace_back(scene_.obstacles[o], model.obstacleShapes()[o]);
}

ContactAdjoint::~ContactAdjoint() = default;

void ContactAdjoint::frameOfObstacleContact(const ContactPoint& p, const NodeMatrix& x0,
                                            const Mat3& lawNormal, Contact& c) const {
  const ContactObstacle& obstacle = obstacles_[p.obstacle];
  const Vec3 start = x0.row(p.node).transpose();
  // The reference velocity and normal as functions of the sample point, at fixed x_n (the same
  // formula as ObstacleContactDetector).
  auto frame = [&](const Vec3& s, Vec3& normal, Vec3& reference) {
    SurfaceSample sample;
    obstacle.sample(s, start, kAnyReach, sample);  // (a box: the entry face, as detection)
    normal = sample.normal;
    const double gap = sample.normal.dot(start - sample.point) - obstacle.thickness();
    const Vec3 surface = obstacle.surfaceVelocity(sample.point);
    reference = surface - sample.normal.dot(surface) * sample.normal - (gap / h_) * sample.normal;
  };
  Mat3 referenceBySample, normalBySample;
  for (int k = 0; k < 3; ++k) {
    Vec3 nPlus, nMinus, refPlus, refMinus;
    frame(p.sample + kFrameStep * Vec3::Unit(k), nPlus, refPlus);
    frame(p.sample - kFrameStep * Vec3::Unit(k), nMinus, refMinus);
    referenceBySample.col(k) = (refPlus - refMinus) / (2.0 * kFrameStep);
    normalBySample.col(k) = (nPlus - nMinus) / (2.0 * kFrameStep);
  }
  // x_n enters the gap directly (d ref / d x_n = -n n^T / h) and the sample point with weight 1;
  // v_n enters the sample point with weight tau h.
  const Mat3 referenceByStart = -(p.normal * p.normal.transpose()) / h_;
  const Mat3& lawVelocity = c.d;  // m_c dL/dw
  const Mat3 bySample =
      -lawVelocity * referenceBySample + c.point.effectiveMass * lawNormal * normalBySample;
  c.frameX = h_ * (-lawVelocity * referenceByStart + bySample);
  c.frameV = h_ * (p.pathFraction * h_) * bySample;
}

void ContactAdjoint::frameOfPair(const ContactPoint& p, const NodeMatrix& x0, const Mat3& lawNormal,
                                 Contact& c) const {
  c.frameX.setZero();
  c.frameV.setZero();
  const Vec3 dx = (x0.row(p.node) - x0.row(p.partner)).transpose();
  const double separation = dx.norm();
  // Coincident nodes took their normal from the approach direction (SelfCollisionDetector); that
  // frame is not a function of x_n and is kept fixed.
  if (!(separation > 0.0) || (dx / separation - p.normal).norm() > 1e-9) return;
  const Mat3 nn = p.normal * p.normal.transpose();
  const Mat3 across = Mat3::Identity() - nn;
  // reference = -(gap / h) n with gap = |dx| - distance, n = dx / |dx|.
  const double gap = -h_ * p.normal.dot(p.reference);
  const Mat3 referenceByDx = -(nn + (gap / separation) * across) / h_;
  const Mat3 normalByDx = across / separation;
  c.frameX = h_ * (-c.d * referenceByDx + c.point.effectiveMass * lawNormal * normalByDx);
}

void ContactAdjoint::prepare(const StepContacts& contacts, const NodeMatrix& x0, double t0,
                             double t1, int step) {
  for (ContactObstacle& o : obstacles_) o.beginStep(t0, t1);
  contacts_.clear();
  pinned_.clear();
  pinnedSlot_.resize(model_.nodeCount(), -1);
  // As the forward's Newton contact solve pins a node (ContactSolver::linearize): a second
  // prescribed direction on the node pins it whole.
  const auto pin = [&](int node, bool stick, const Vec3& normal, const Mat3& dOverMass) {
    int& slot = pinnedSlot_[node];
    if (slot < 0) {
      slot = static_cast<int>(pinned_.size());
      pinned_.push_back({node, -1,
                         stick ? Mat3(Mat3::Identity()) : Mat3(normal * normal.transpose()),
                         Mat3::Identity() + dOverMass.transpose(), normal});
    } else {
      pinned_[slot].projector.setIdentity();
      pinned_[slot].s.setZero();
    }
  };
  for (const ContactPoint& p : contacts.points) {
    if (p.branch != ContactBranch::Stick && p.branch != ContactBranch::Slip) continue;
    Contact c;
    c.point = p;
    c.velocityChange = p.impulse / p.effectiveMass;
    const Vec3 free = p.velocity - c.velocityChange;
    const ContactLawJacobian law =
        differentiateSignoriniCoulomb(p.branch, p.normal, p.friction, free);
    c.d = c.point.effectiveMass * law.velocity;
    c.frictionRate = h_ * c.point.effectiveMass * law.friction;
    if (p.partner < 0)
      frameOfObstacleContact(p, x0, law.normal, c);
    else
      frameOfPair(p, x0, law.normal, c);
    contacts_.push_back(c);
    // (Its row of wbar = M^-1 G^T D^T y is d^T z / m for an uncoupled contact: S = I + d^T / m.)
    if (p.partner < 0)
      pin(p.node, p.branch == ContactBranch::Stick, p.normal, c.d / model_.mass[p.node]);
  }
  for (const PinnedContact& n : pinned_) pinnedSlot_[n.node] = -1;  // (ready for the next step)

  // Contacts sharing a node couple through T (ContactAdjoint.h).
  const int count = size();
  touching_.assign(model_.nodeCount(), 0);
  coupled_ = false;
  for (const Contact& c : contacts_) {
    coupled_ = coupled_ || ++touching_[c.point.node] > 1;
    if (c.point.partner >= 0) coupled_ = coupled_ || ++touching_[c.point.partner] > 1;
  }
  // A pair whose nodes touch nothing else: y = z_a - z_b and wbar = (d^T y / m_a, -d^T y / m_b),
  // so S keeps (m_a z_a + m_b z_b) / (m_a + m_b) and maps z_a - z_b by I + d^T / m_c.
  for (const Contact& c : contacts_) {
    if (c.point.partner < 0 || touching_[c.point.node] > 1 || touching_[c.point.partner] > 1)
      continue;
    pinned_.push_back({c.point.node, c.point.partner,
                       c.point.branch == ContactBranch::Stick
                           ? Mat3(Mat3::Identity())
                           : Mat3(c.point.normal * c.point.normal.transpose()),
                       Mat3::Identity() + c.d.transpose() / c.point.effectiveMass, c.point.normal});
  }
  if (!coupled_) return;
  std::vector<std::vector<std::pair<int, double>>> sharing(
      model_.nodeCount());  // node -> (contact, sign)
  for (int k = 0; k < count; ++k) {
    sharing[contacts_[k].point.node].emplace_back(k, 1.0);
    if (contacts_[k].point.partner >= 0) sharing[contacts_[k].point.partner].emplace_back(k, -1.0);
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < 3 * count; ++k) entries.emplace_back(k, k, 1.0);
  for (int node = 0; node < model_.nodeCount(); ++node) {
    const auto& list = sharing[node];
    if (list.size() < 2) continue;
    const double inverseMass = 1.0 / model_.mass[node];
    for (const auto& [c, sc] : list)
      for (const auto& [other, so] : list) {
        if (c == other) continue;
        // T^T_{c,other} = -H_{c,other} D_other^T, H_{c,other} = sum over shared nodes s_c s_o / m.
        const Mat3 block = -(sc * so * inverseMass) * contacts_[other].d.transpose();
        for (int e = 0; e < 3; ++e)
          for (int f = 0; f < 3; ++f)
            if (block(e, f) != 0.0) entries.emplace_back(3 * c + e, 3 * other + f, block(e, f));
      }
  }
  tTransposed_.resize(3 * count, 3 * count);
  tTransposed_.setFromTriplets(entries.begin(), entries.end());
  // A node sticking to two obstacles (or pairs sticking around a node) has no unique impulse
  // split: two sticks on one node give T^T = [I I; I I], a stick and a slip [I I; S I] with S
  // sharing I's normal direction. The node's motion depends on the total impulse only, which
  // every solution gives; the forward picked one split. A shift of the diagonal makes the solve
  // pick the minimum-norm split (as the shift goes to 0), and the direct fallback's augmented
  // system takes the same shifted block. Which groups of coupled contacts are singular is read
  // from their singular values: rounding leaves the stick-slip block's zeros slightly off zero,
  // where the sparse LU finds no zero pivot, and the unshifted augmented system then fails
  // UMFPACK or gives a wrong gradient (docs/how-it-works/backward.md).
  for (const std::vector<int>& group : coupledGroups(sharing, count)) {
    const int size = 3 * static_cast<int>(group.size());
    Eigen::MatrixXd block(size, size);
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j)
        block(i, j) = tTransposed_.coeff(3 * group[i / 3] + i % 3, 3 * group[j / 3] + j % 3);
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(block).singularValues();
    if (sigma[size - 1] > kSingularCouplingRatio * sigma[0]) continue;
    for (int k : group)
      for (int e = 0; e < 3; ++e)
        tTransposed_.coeffRef(3 * k + e, 3 * k + e) += kSingularCouplingShift;
  }
  tTransposed_.makeCompressed();
  tSolver_.compute(tTransposed_);
  if (tSolver_.info() != Eigen::Success)
    throw NumericalError(
        step, "backward",
        "the contacts sharing a node have no unique impulse split (singular contact coupling "
        "of " +
            std::to_string(count) +
            " contacts, also with the singular groups' diagonal shifted by 1e-9)");
}

void ContactAdjoint::applyTransposed(const NodeMatrix& z, NodeMatrix& wbar,
                                     Eigen::MatrixX3d& y) const {
  const int count = size();
  y.resize(count, 3);
  for (int k = 0; k < count; ++k) {
    const Contact& c = contacts_[k];
    y.row(k) = z.row(c.point.node);
    if (c.point.partner >= 0) y.row(k) -= z.row(c.point.partner);
  }
  if (coupled_) {
    work_.resize(3 * count);
    for (int k = 0; k < count; ++k) work_.segment<3>(3 * k) = y.row(k).transpose();
    work_ = tSolver_.solve(work_).eval();
    for (int k = 0; k < count; ++k) y.row(k) = work_.segment<3>(3 * k).transpose();
  }
  wbar.setZero(z.rows(), 3);
  for (int k = 0; k < count; ++k) {
    const Contact& c = contacts_[k];
    const Vec3 v = c.d.transpose() * y.row(k).transpose();
    wbar.row(c.point.node) += v.transpose() / model_.mass[c.point.node];
    if (c.point.partner >= 0)
      wbar.row(c.point.partner) -= v.transpose() / model_.mass[c.point.partner];
  }
}

void ContactAdjoint::appendTransposedBlocks(
    std::vector<Eigen::Triplet<double>>& b, std::vector<Eigen::Triplet<double>>& minusG,
    std::vector<Eigen::Triplet<double>>& tTransposed) const {
  const int m = model_.nodeCount();
  for (int k = 0; k < size(); ++k) {
    const Contact& c = contacts_[k];
    for (int side = 0; side < 2; ++side) {
      const int node = side == 0 ? c.point.node : c.point.partner;
      if (node < 0) continue;
      const double sign = side == 0 ? 1.0 : -1.0;
      for (int d = 0; d < 3; ++d) {
        minusG.emplace_back(3 * k + d, d * m + node, -sign);
        for (int e = 0; e < 3; ++e)
          if (c.d(e, d) != 0.0)
            b.emplace_back(d * m + node, 3 * k + e, sign * c.d(e, d) / model_.mass[node]);
      }
    }
  }
  if (coupled_) {
    for (int k = 0; k < tTransposed_.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(tTransposed_, k); it; ++it)
        tTransposed.emplace_back(it.row(), it.col(), it.value());
  } else {
    for (int k = 0; k < 3 * size(); ++k) tTransposed.emplace_back(k, k, 1.0);
  }
}

void ContactAdjoint::addStateGradients(const Eigen::MatrixX3d& y, NodeMatrix& dLdx0,
                                       NodeMatrix& dLdv0) const {
  for (int k = 0; k < size(); ++k) {
    const Contact& c = contacts_[k];
    const Vec3 yk = y.row(k).transpose();
    const Vec3 byStart = c.frameX.transpose() * yk;
    dLdx0.row(c.point.node) += byStart.transpose();
    if (c.point.partner >= 0)
      dLdx0.row(c.point.partner) -= byStart.transpose();
    else
      dLdv0.row(c.point.node) += (c.frameV.transpose() * yk).transpose();
  }
}

void ContactAdjoint::addParameterGradients(const std::vector<SceneParameter>& parameters,
                                           const Eigen::MatrixX3d& y, const NodeMatrix& wbar,
                                           const NodeMatrix& x0, const NodeMatrix& v0,
                                           const NodeMatrix& x1, Eigen::VectorXd& gradient) const {
  using Kind = SceneParameter::Kind;
  const Vec3 g = scene_.gravity ? *scene_.gravity : Vec3::Zero();
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const SceneParameter& p = parameters[k];
    double d = 0.0;
    if (p.kind == Kind::ObstacleFriction) {
      for (int c = 0; c < size(); ++c)
        if (contacts_[c].point.obstacle == p.index)
          d += y.row(c).dot(contacts_[c].frictionRate.transpose());
    } else if (p.kind == Kind::SelfCollisionFriction) {
      // A pair's coefficient is the mean of its two nodes' cloths' (SelfCollisionDetector).
      for (int c = 0; c < size(); ++c) {
        const Contact& ct = contacts_[c];
        if (ct.point.partner < 0) continue;
        const double share = 0.5 * ((model_.clothOf(ct.point.node) == p.cloth) +
                                    (model_.clothOf(ct.point.partner) == p.cloth));
        d += share * y.row(c).dot(ct.frictionRate.transpose());
      }
    } else if (p.kind == Kind::Density) {
      const int first = model_.vertexOffset[p.cloth], last = model_.vertexOffset[p.cloth + 1];
      const double density = scene_.cloths[p.cloth].material.density;
      auto inCloth = [&](int node) { return node >= first && node < last; };
      // ParameterPartials was handed z + wbar (the force-like parameters' S^T z), but density's
      // inertia term belongs to z alone: take wbar's share back out.
      for (int i = first; i < last; ++i) {
        const Vec3 inertia = (x1.row(i) - x0.row(i) - h_ * v0.row(i)).transpose() - h_ * h_ * g;
        d += (model_.mass[i] / density) * wbar.row(i).dot(inertia.transpose());
      }
      // The law's side: f = M (v_n + h g) + ..., the node velocities M^-1 (f + r) and the
      // effective masses all scale with the cloth's density (dm_i / drho = m_i / rho).
      for (int c = 0; c < size(); ++c) {
        const Contact& ct = contacts_[c];
        if (!inCloth(ct.point.node) && !(ct.point.partner >= 0 && inCloth(ct.point.partner)))
          continue;
        Vec3 freeRate = Vec3::Zero();
        double inverseMassRate = 0.0;  // d (1/m_c) / d rho
        for (int side = 0; side < 2; ++side) {
          const int node = side == 0 ? ct.point.node : ct.point.partner;
          if (node < 0 || !inCloth(node)) continue;
          const double sign = side == 0 ? 1.0 : -1.0;
          const Vec3 v1 = (x1.row(node) - x0.row(node)).transpose() / h_;
          // d/drho of (f_i + r_i) / m_i at fixed impulses: (v_n + h g - v_{n+1}) / rho.
          freeRate += sign * (v0.row(node).transpose() + h_ * g - v1) / density;
          inverseMassRate -= 1.0 / (model_.mass[node] * density);
        }
        const double massRate =
            -ct.point.effectiveMass * ct.point.effectiveMass * inverseMassRate;  // d m_c / d rho
        // w_c holds -r_c / m_c = -du: its rate at fixed r_c is du (d m_c / d rho) / m_c.
        freeRate += ct.velocityChange * massRate / ct.point.effectiveMass;
        const Vec3 sensitivity = h_ * (massRate * ct.velocityChange + ct.d * freeRate);
        d += y.row(c).dot(sensitivity.transpose());
      }
    }
    gradient[static_cast<int>(k)] += d;
  }
}

}  // namespace weft
