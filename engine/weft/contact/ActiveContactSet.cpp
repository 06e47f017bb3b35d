#include <weft/contact/ActiveContactSet.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft {
namespace {

// Tikhonov shift of C C^T (its diagonal is 1 or 2): keeps the factorisation defined when rows are
// dependent (a node held by two sticking obstacles, a closed loop of sticking pairs). Dependent
// rows may also have inconsistent targets (a loop of pairs each asking for its own gap), whose
// least-squares part the shift amplifies by 1/shift and round-off by the condition number, also
// about 1/shift: 1e-7 keeps that product near 1e-2 of the inconsistency, while a consistent
// projection is exact to about 1e-7 before the refinement pass (project()).
constexpr double kGramShift = 1e-7;
// Branch switches of one contact in one step before it may no longer take off, and before it
// keeps its branch.
// Smallest floor eps of |u_T| in the friction Hessian (m/s). The friction's stiffness
// mu r_N / |u_T| near rest is what Newton has to resolve; below about a millimetre per second it
// dwarfs the cloth's and the solve stalls. A settled slide slower than eps becomes stick.
constexpr double kMinimumSmoothing = 1e-3;
constexpr int kFlipsBeforeHolding = 4, kFlipsBeforeFreezing = 8;

}  // namespace

void ActiveContactSet::reset(const std::vector<ContactPoint>& obstacleContacts,
                             const std::vector<ContactPoint>& pairs, const NodeMatrix& x0,
                             const Eigen::VectorXd& mass, double h, double velocityTolerance) {
  x0_ = &x0;
  h_ = h;
  smoothing_ = std::max(velocityTolerance, kMinimumSmoothing);
  // Remember how the last step left each node's obstacle contact, for guessBranches.
  if (previous_.size() != static_cast<std::size_t>(x0.rows()))
    previous_.assign(x0.rows(), Previous{});
  for (int node : rememberedNodes_) previous_[node] = Previous{};
  rememberedNodes_.clear();
  for (const Contact& c : contacts_)
    if (c.point.partner < 0 && c.point.branch != ContactBranch::TakeOff &&
        previous_[c.point.node].branch == ContactBranch::None) {
      previous_[c.point.node] = Previous{c.point.branch, c.slipLimit};
      rememberedNodes_.push_back(c.point.node);
    }
  contacts_.clear();
  rows_.clear();
  lastChange_ = 0.0;
  auto add = [&](const ContactPoint& detected, double effectiveMass) {
    Contact c;
    c.point = detected;
    c.point.branch = ContactBranch::TakeOff;
    c.point.impulse.setZero();
    c.point.velocity.setZero();
    c.point.effectiveMass = effectiveMass;
    contacts_.push_back(c);
  };
  for (const ContactPoint& c : obstacleContacts) add(c, mass[c.node]);
  for (const ContactPoint& c : pairs)
    add(c, mass[c.node] * mass[c.partner] / (mass[c.node] + mass[c.partner]));
}

Vec3 ActiveContactSet::relativeVelocity(const Contact& c, const NodeMatrix& x) const {
  Vec3 u = (x.row(c.point.node) - x0_->row(c.point.node)).transpose() / h_;
  if (c.point.partner >= 0)
    u -= (x.row(c.point.partner) - x0_->row(c.point.partner)).transpose() / h_;
  return u - c.point.reference;
}

void ActiveContactSet::guessBranches(const NodeMatrix& x) {
  for (Contact& c : contacts_) {
    c.point.velocity = relativeVelocity(c, x);
    c.slipLimit = 0.0;
    c.point.impulse.setZero();
    c.flips = 0;
    c.point.branch = c.point.normal.dot(c.point.velocity) >= 0.0 ? ContactBranch::TakeOff
                     : c.point.friction > 0.0                    ? ContactBranch::Stick
                                                                 : ContactBranch::Slip;
    // A node that rested or slid on an obstacle last step most likely still does: start from
    // that branch (and friction) instead of stick, which saves a release round per step.
    if (c.point.branch != ContactBranch::TakeOff && c.point.partner < 0 &&
        previous_[c.point.node].branch != ContactBranch::None) {
      c.point.branch = previous_[c.point.node].branch;
      c.slipLimit = previous_[c.point.node].slipLimit;
    }
  }
  buildRows();
}

void ActiveContactSet::buildRows() {
  // Rows: dir . (x_a - x_b) = dir . (x0_a - x0_b + h reference), i.e. dir . u = 0.
  rows_.clear();
  for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
    const Contact& c = contacts_[k];
    if (c.point.branch == ContactBranch::TakeOff) continue;
    Vec3 start = x0_->row(c.point.node).transpose() + h_ * c.point.reference;
    if (c.point.partner >= 0) start -= x0_->row(c.point.partner).transpose();
    auto addRow = [&](const Vec3& dir) {
      rows_.push_back(Row{c.point.node, c.point.partner, k, dir, dir.dot(start)});
    };
    if (c.point.branch == ContactBranch::Slip) {
      addRow(c.point.normal);
    } else {
      for (int axis = 0; axis < 3; ++axis) addRow(Vec3::Unit(axis));
    }
  }
  const int n = static_cast<int>(rows_.size());
  rowValues_.resize(n);
  lambda_.resize(n);
  if (n == 0) return;

  // C C^T: rows interact through the nodes they share. (node, row, sign) sorted by node.
  struct Touch {
    int node, row;
    double sign;
  };
  std::vector<Touch> touches;
  touches.reserve(2 * n);
  for (int r = 0; r < n; ++r) {
    touches.push_back(Touch{rows_[r].a, r, 1.0});
    if (rows_[r].b >= 0) touches.push_back(Touch{rows_[r].b, r, -1.0});
  }
  std::sort(touches.begin(), touches.end(), [](const Touch& p, const Touch& q) {
    return p.node != q.node ? p.node < q.node : p.row < q.row;
  });
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < n; ++r) entries.emplace_back(r, r, kGramShift);
  for (std::size_t begin = 0; begin < touches.size();) {
    std::size_t end = begin;
    while (end < touches.size() && touches[end].node == touches[begin].node) ++end;
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t j = begin; j < end; ++j) {
        const double value = touches[i].sign * touches[j].sign *
                             rows_[touches[i].row].dir.dot(rows_[touches[j].row].dir);
        if (value != 0.0) entries.emplace_back(touches[i].row, touches[j].row, value);
      }
    begin = end;
  }
  gram_.resize(n, n);
  gram_.setFromTriplets(entries.begin(), entries.end());
  gramFactor_.compute(gram_);
  if (gramFactor_.info() != Eigen::Success)
    throw std::runtime_error("contact constraint Gram matrix not factorised");
}

void ActiveContactSet::multipliers(const NodeMatrix& v, Eigen::VectorXd& lambda) const {
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const Row& row = rows_[r];
    double value = row.dir.dot(v.row(row.a).transpose());
    if (row.b >= 0) value -= row.dir.dot(v.row(row.b).transpose());
    rowValues_[r] = value;
  }
  lambda = gramFactor_.solve(rowValues_);
}

void ActiveContactSet::project(NodeMatrix& v, bool affine) const {
  // v <- v - C^T (C C^T)^-1 (C v - target), and once more for what the shift left.
  for (int pass = 0; pass < 2; ++pass) {
    multipliers(v, lambda_);
    if (affine) {
      for (std::size_t r = 0; r < rows_.size(); ++r) rowValues_[r] -= rows_[r].target;
      lambda_ = gramFactor_.solve(rowValues_);
    }
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Row& row = rows_[r];
      v.row(row.a) -= lambda_[r] * row.dir.transpose();
      if (row.b >= 0) v.row(row.b) += lambda_[r] * row.dir.transpose();
    }
  }
}

void ActiveContactSet::projectDirection(NodeMatrix& d) const {
  if (!rows_.empty()) project(d, false);
}

void ActiveContactSet::projectPositions(NodeMatrix& x) const {
  if (!rows_.empty()) project(x, true);
}

void ActiveContactSet::refreshVelocities(const NodeMatrix& x) {
  for (Contact& c : contacts_) c.point.velocity = relativeVelocity(c, x);
}

Vec3 ActiveContactSet::slide(const Contact& c, const NodeMatrix& x) const {
  const Vec3 u = relativeVelocity(c, x);
  return u - c.point.normal.dot(u) * c.point.normal;
}

Vec3 ActiveContactSet::frictionImpulse(const Contact& c, const NodeMatrix& x) const {
  // Coulomb's -mu r_N u_T / |u_T| exactly (the gradient of the convex potential mu r_N |u_T|,
  // frictionPotential); at u_T = 0 the zero subgradient.
  const Vec3 uT = slide(c, x);
  const double speed = uT.norm();
  return speed > 0.0 ? Vec3((-c.slipLimit / speed) * uT) : Vec3::Zero();
}

void ActiveContactSet::addFriction(const NodeMatrix& x, double h, NodeMatrix& residual) const {
  for (const Contact& c : contacts_) {
    if (c.point.branch != ContactBranch::Slip || c.slipLimit == 0.0) continue;
    const Vec3 f = h * frictionImpulse(c, x);
    residual.row(c.point.node) += f.transpose();
    if (c.point.partner >= 0) residual.row(c.point.partner) -= f.transpose();
  }
}

double ActiveContactSet::frictionPotential(const NodeMatrix& x) const {
  // Phi = sum mu r_N |u_T|: its gradient in x_a is mu r_N u_T / (|u_T| h) = -friction / h.
  double phi = 0.0;
  for (const Contact& c : contacts_)
    if (c.point.branch == ContactBranch::Slip && c.slipLimit > 0.0)
      phi += c.slipLimit * slide(c, x).norm();
  return phi;
}

void ActiveContactSet::prepareFrictionHessian(const NodeMatrix& x) {
  for (Contact& c : contacts_) {
    if (c.point.branch != ContactBranch::Slip || c.slipLimit == 0.0) continue;
    c.hessianSlide = slide(c, x);
    c.hessianNorm = std::max(c.hessianSlide.norm(), smoothing_);
  }
}

void ActiveContactSet::addFrictionHessian(const NodeMatrix& d, NodeMatrix& out) const {
  // h^2 Hessian of Phi on (d_a - d_b): mu r_N / |u_T| (T - u_T u_T^T / |u_T|^2), T the tangent
  // projector, with |u_T| floored at eps in both places (near rest the true curvature is
  // unbounded); positive semi-definite, so CG stays valid.
  for (const Contact& c : contacts_) {
    if (c.point.branch != ContactBranch::Slip || c.slipLimit == 0.0) continue;
    Vec3 rel = d.row(c.point.node).transpose();
    if (c.point.partner >= 0) rel -= d.row(c.point.partner).transpose();
    const Vec3 tangential = rel - c.point.normal.dot(rel) * c.point.normal;
    const Vec3 f =
        (c.slipLimit / c.hessianNorm) *
        (tangential -
         (c.hessianSlide.dot(tangential) / (c.hessianNorm * c.hessianNorm)) * c.hessianSlide);
    out.row(c.point.node) += f.transpose();
    if (c.point.partner >= 0) out.row(c.point.partner) -= f.transpose();
  }
}

int ActiveContactSet::update(const NodeMatrix& x, const NodeMatrix& residual,
                             double velocityTolerance, bool settled) {
  // Multipliers: C^T lambda = -residual in the least-squares sense; h r = C^T lambda per contact.
  if (!rows_.empty()) {
    multipliers(residual, lambda_);
    lambda_ = -lambda_;
  }
  for (Contact& c : contacts_) c.point.impulse.setZero();
  for (std::size_t r = 0; r < rows_.size(); ++r)
    contacts_[rows_[r].contact].point.impulse += (lambda_[r] / h_) * rows_[r].dir;

  int changed = 0;
  lastChange_ = 0.0;
  blocked_ = 0;
  for (Contact& c : contacts_) {
    c.point.velocity = relativeVelocity(c, x);
    const double impulseTolerance = c.point.effectiveMass * velocityTolerance;
    const double normalImpulse = c.point.normal.dot(c.point.impulse);
    const ContactBranch before = c.point.branch;
    // Anti-cycling: a contact that keeps switching is first kept active (no more take-off), and
    // finally frozen in its branch for the rest of the step.
    // Releasing (stick -> take-off or slip, slip -> take-off or stick) is judged on a settled
    // solve only, when the multipliers are the contact impulses; activating a contact that
    // penetrates is judged at every iterate.
    const bool mayRelease = settled && c.flips < kFlipsBeforeHolding,
               mayChange = c.flips < kFlipsBeforeFreezing;
    switch (mayChange ? c.point.branch : ContactBranch::None) {
      case ContactBranch::TakeOff:
        if (c.point.normal.dot(c.point.velocity) < -velocityTolerance) {
          c.point.branch = c.point.friction > 0.0 ? ContactBranch::Stick : ContactBranch::Slip;
          c.slipLimit = 0.0;
        }
        break;
      case ContactBranch::Stick: {
        const Vec3 tangential = c.point.impulse - normalImpulse * c.point.normal;
        // The tangential release comes first: a node held in all three directions may need a
        // pulling normal impulse only because it is held tangentially; freed at once it would
        // penetrate, and be caught again (a cycle). So a pulling node slides first (with no
        // friction, the cone of a non-positive r_N being empty), and takes off from slip.
        const double cone = c.point.friction * std::max(normalImpulse, 0.0);
        if (tangential.norm() > cone + impulseTolerance && mayRelease) {
          // The cone cannot hold it: slide against the direction the holding force pointed.
          c.point.branch = ContactBranch::Slip;
          c.slipLimit = cone;
        } else if (normalImpulse < -impulseTolerance && mayRelease) {
          c.point.branch = ContactBranch::TakeOff;
        }
        break;
      }
      case ContactBranch::Slip: {
        if (normalImpulse < -impulseTolerance && mayRelease) {
          c.point.branch = ContactBranch::TakeOff;
          c.slipLimit = 0.0;
          break;
        }
        // The slide and the friction's size are judged on a settled solve only: right after a
        // stick -> slip switch the node has not moved yet. The friction's direction needs no
        // judging: it follows the slide inside the Newton solve (frictionImpulse).
        if (!settled) break;
        const double speed = slide(c, x).norm();
        if (c.point.friction > 0.0 && speed <= smoothing_) {
          // Stopped: the cone holds it (if not, the stick check releases it again).
          c.point.branch = ContactBranch::Stick;
          c.slipLimit = 0.0;
          break;
        }
        const double limit = c.point.friction * std::max(normalImpulse, 0.0);
        lastChange_ = std::max(lastChange_, std::abs(limit - c.slipLimit) / c.point.effectiveMass);
        c.slipLimit = limit;
        break;
      }
      default:
        break;
    }
    if (c.point.branch != before)
      ++changed, ++c.flips;
    else if (settled && (c.flips >= kFlipsBeforeHolding) && violatesLaw(c, velocityTolerance))
      ++blocked_;
    if (c.point.branch == ContactBranch::TakeOff) c.point.impulse.setZero();
    if (c.point.branch == ContactBranch::Slip)
      c.point.impulse = normalImpulse * c.point.normal + frictionImpulse(c, x);
  }
  if (changed > 0) buildRows();
  return changed;
}

bool ActiveContactSet::violatesLaw(const Contact& c, double velocityTolerance) const {
  const double impulseTolerance = c.point.effectiveMass * velocityTolerance;
  const double rN = c.point.normal.dot(c.point.impulse), uN = c.point.normal.dot(c.point.velocity);
  const Vec3 rT = c.point.impulse - rN * c.point.normal;
  switch (c.point.branch) {
    case ContactBranch::TakeOff:
      return uN < -velocityTolerance;
    case ContactBranch::Stick:
      return rN < -impulseTolerance || rT.norm() > c.point.friction * rN + impulseTolerance;
    case ContactBranch::Slip:
      return rN < -impulseTolerance ||
             std::abs(rT.norm() - c.point.friction * std::max(rN, 0.0)) > impulseTolerance;
    default:
      return false;
  }
}

void ActiveContactSet::record(StepContacts& out) const {
  out.points.clear();
  out.points.reserve(contacts_.size());
  for (const Contact& c : contacts_) out.points.push_back(c.point);
  out.sweepChange = lastChange_;
  out.pairLayers = 0;
}

}  // namespace weft
