#include <weft/diff/AdjointSystem.h>

#include <weft/core/Error.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <utility>

namespace weft {

AdjointSystem::AdjointSystem(std::shared_ptr<const Model> model)
    : compiled_(std::move(model)),
      model_(compiled_->cloth()),
      h_(compiled_->dt()),
      constraints_(compiled_->instantiateConstraints()) {
  system_ = assembleSystemMatrix(model_.mass, constraints_, h_);
  for (const auto& c : constraints_) {
    anyDerivative_ = anyDerivative_ || c->hasDerivative();
    dependsOnStart_ = dependsOnStart_ || c->dependsOnStart();
    rows_.emplace_back(NodeMatrix::Zero(c->hasDerivative() ? c->rowCount() : 0, 3));
  }
  if (!cholesky_.factorize(system_))
    throw NumericalError(0, "backward", "system matrix P is not positive definite");
  assembly_ = std::make_unique<HessianAssembly>(system_);
  hessianCholesky_.orderByNodes(system_);
}

AdjointSystem::~AdjointSystem() = default;

void AdjointSystem::addStartGradient(const NodeMatrix& start, const NodeMatrix& q,
                                     NodeMatrix& out) const {
  for (const auto& c : constraints_)
    if (c->dependsOnStart()) c->addStartGradient(start, q, h_ * h_, out);
}

void AdjointSystem::prepare(const NodeMatrix& x, const ContactAdjoint* contact) {
  preparedX_ = x;  // kept for factorClampedHessian (same size every step: no allocation)
  for (auto& c : constraints_)
    if (c->hasDerivative())
      c->prepareDerivative(x, false);  // exact derivative (Eq. 18), not clamped
  contact_ = contact && contact->size() > 0 ? contact : nullptr;
  pinnedBlocks_.clear();
  if (!contact_) return;
  for (const ContactAdjoint::PinnedContact& p : contact_->pinnedContacts()) {
    PinnedBlock b{p.node, p.partner, p.projector, Mat3::Zero(), 1.0, 0.0, model_.mass[p.node]};
    if (p.partner >= 0) {
      // A pair: z_a = c + alpha r, z_b = c - beta r for the mean c and the relative r, with
      // alpha = m_c / m_a and beta = m_c / m_b (alpha + beta = 1).
      const double ma = model_.mass[p.node], mb = model_.mass[p.partner];
      b.alpha = mb / (ma + mb);
      b.beta = ma / (ma + mb);
      b.mass = ma * mb / (ma + mb);
    }
    if (!p.projector.isIdentity(0.0)) {
      // Slipping: S's tangent block is I - g (I - t t^T) (t: the slip direction, g =
      // mu |du_N| / |w_T| < 1), so z's tangent part is the factor's solution mapped by its
      // inverse. Where 1 - g is below m_c / (alpha P_aa + beta P_bb) (an obstacle's node:
      // m / P_aa), K's column there is closer to M's (S ~ 0, as sticking) than to K_e's, and the
      // direction is pinned instead.
      Vec3 t1 = p.normal.unitOrthogonal(), t2 = p.normal.cross(t1);
      Eigen::Matrix<double, 3, 2> tangent;
      tangent << t1, t2;
      const Eigen::Matrix2d block = tangent.transpose() * p.s * tangent;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(0.5 * (block + block.transpose()));
      double stiffness = b.alpha * system_.coeff(p.node, p.node);
      if (p.partner >= 0) stiffness += b.beta * system_.coeff(p.partner, p.partner);
      const double floor = b.mass / stiffness;
      for (int k = 0; k < 2; ++k) {
        const Vec3 e = tangent * eigen.eigenvectors().col(k);
        const double lambda = eigen.eigenvalues()[k];
        if (lambda > floor)
          b.freeMap += e * e.transpose() / lambda;
        else
          b.pinned += e * e.transpose();
      }
    }
    pinnedBlocks_.push_back(b);
  }
}

void AdjointSystem::multiplyP(const NodeMatrix& in, NodeMatrix& out) const {
  out = system_ * in;
}

void AdjointSystem::multiplyDeltaP(const NodeMatrix& in, NodeMatrix& out) const {
  // Delta P in = h^2 sum_i A_i^T w_i D_i A_i in (Eq. 19), with applyDerivative giving w_i D_i A_i
  // in.
  out.setZero(in.rows(), 3);
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    if (!constraints_[c]->hasDerivative()) continue;
    constraints_[c]->applyDerivative(in, rows_[c]);
    constraints_[c]->gather(rows_[c], h_ * h_, out);
  }
}

void AdjointSystem::multiplyK(const NodeMatrix& in, NodeMatrix& out) const {
  if (contact_) {
    // K z = (P - Delta P)(z + wbar) - M wbar, wbar = R'^T z (ContactAdjoint.h).
    contact_->applyTransposed(in, contactWbar_, contactY_);
    contactSum_ = in + contactWbar_;
    multiplyP(contactSum_, out);
    out -= model_.mass.asDiagonal() * contactWbar_;
    for (std::size_t c = 0; c < constraints_.size(); ++c) {
      if (!constraints_[c]->hasDerivative()) continue;
      constraints_[c]->applyDerivative(contactSum_, rows_[c]);
      constraints_[c]->gather(rows_[c], -h_ * h_, out);
    }
    return;
  }
  multiplyElastic(in, out);
}

void AdjointSystem::multiplyElastic(const NodeMatrix& in, NodeMatrix& out) const {
  multiplyP(in, out);
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    if (!constraints_[c]->hasDerivative()) continue;
    constraints_[c]->applyDerivative(in, rows_[c]);
    constraints_[c]->gather(rows_[c], -h_ * h_, out);
  }
}

void AdjointSystem::multiplyCoupling(const NodeMatrix& in, NodeMatrix& out) const {
  if (!contact_) {
    multiplyDeltaP(in, out);
    return;
  }
  multiplyK(in, work_);
  multiplyP(in, out);
  out -= work_;
}

void AdjointSystem::solveP(NodeMatrix& inOut) {
  cholesky_.solveInPlace(inOut);
}

void AdjointSystem::precondition(NodeMatrix& inOut, bool hessian) {
  const auto solve = [&](NodeMatrix& v) {
    if (hessian)
      solveClampedHessian(v);
    else
      solveP(v);
  };
  if (!contact_ || !contactPreconditioning_ || pinnedBlocks_.empty()) {
    solve(inOut);
    return;
  }
  // (AdjointSystem.h) w = (I - Pi) F^-1 (I - Pi) g, u = Q w on contact nodes (w elsewhere),
  // then z = u + V Pi (g - K u). On a pair, Pi acts on the relative part: (I - Pi) removes
  // Pi (g_a - g_b) / 2 from g_a and adds it to g_b, Q maps w_a - w_b and keeps the mean.
  preconditionRhs_ = inOut;
  for (const PinnedBlock& b : pinnedBlocks_) {
    if (b.partner < 0) {
      inOut.row(b.node) -= (b.pinned * inOut.row(b.node).transpose()).transpose();
    } else {
      const Vec3 half = 0.5 * b.pinned * (inOut.row(b.node) - inOut.row(b.partner)).transpose();
      inOut.row(b.node) -= half.transpose();
      inOut.row(b.partner) += half.transpose();
    }
  }
  solve(inOut);
  for (const PinnedBlock& b : pinnedBlocks_) {
    if (b.partner < 0) {
      inOut.row(b.node) = (b.freeMap * inOut.row(b.node).transpose()).transpose();
    } else {
      const Vec3 wa = inOut.row(b.node).transpose(), wb = inOut.row(b.partner).transpose();
      const Vec3 mean = b.beta * wa + b.alpha * wb, relative = b.freeMap * (wa - wb);
      inOut.row(b.node) = (mean + b.alpha * relative).transpose();
      inOut.row(b.partner) = (mean - b.beta * relative).transpose();
    }
  }
  multiplyK(inOut, preconditionProduct_);
  // K's columns along the pinned directions: M alone on an obstacle's node (K M^-1 Pi e = Pi e);
  // on a pair, z = (e / m_a, -e / m_b) with e along Pi has S z = 0 and K z = (e, -e).
  const auto residual = [&](int node) {
    return Vec3((preconditionRhs_.row(node) - preconditionProduct_.row(node)).transpose());
  };
  for (const PinnedBlock& b : pinnedBlocks_) {
    if (b.partner < 0) {
      inOut.row(b.node) += (b.pinned * residual(b.node)).transpose() / model_.mass[b.node];
    } else {
      const Vec3 e = 0.5 * b.pinned * (residual(b.node) - residual(b.partner));
      inOut.row(b.node) += e.transpose() / model_.mass[b.node];
      inOut.row(b.partner) -= e.transpose() / model_.mass[b.partner];
    }
  }
}

bool AdjointSystem::factorClampedHessian() {
  if (preparedX_.rows() != nodeCount()) return false;
  for (auto& c : constraints_)
    if (c->hasDerivative()) c->prepareDerivative(preparedX_, true);
  // Into the kept matrix: its pattern never changes, so each factorisation overwrites the values.
  assembly_->assemble(constraints_, -h_ * h_, clamped_);
  // Back to the exact derivative: K's products must stay those of Eq. 19.
  for (auto& c : constraints_)
    if (c->hasDerivative()) c->prepareDerivative(preparedX_, false);
  return hessianCholesky_.factorize(clamped_);
}

double AdjointSystem::hessianFlopRatio() const {
  return cholesky_.blockFactorFlopRatio(static_cast<double>(system_.nonZeros()));
}

double AdjointSystem::hessianIterationCost() const {
  const double product = 18.0 * static_cast<double>(system_.nonZeros());
  const double entriesP = cholesky_.factorEntries();
  const double entriesH =
      hessianCholesky_.factorEntries() > 0.0 ? hessianCholesky_.factorEntries() : 9.0 * entriesP;
  return (4.0 * entriesH + product) / (12.0 * entriesP + product);
}

double AdjointSystem::hessianFactorCost() const {
  return kFactorCostScale * std::sqrt(hessianFlopRatio());
}

void AdjointSystem::solveClampedHessian(NodeMatrix& inOut) {
  // NodeMatrix storage is column-major: its data is the flat 3m vector assembleK indexes.
  hessianCholesky_.solveInPlace(inOut.data(), 1);
}

Eigen::SparseMatrix<double> AdjointSystem::assembleK() const {
  // P (x) I_3 - Delta P (Eq. 19) from the prepared derivatives' element blocks.
  Eigen::SparseMatrix<double> k;
  assembly_->assemble(constraints_, -h_ * h_, k);
  return k;
}

Eigen::SparseMatrix<double> AdjointSystem::assembleSystem() const {
  Eigen::SparseMatrix<double> k = assembleK();
  if (!contact_) return k;
  // [ K  (K - M) B ; -G  T^T ] (ContactAdjoint::appendTransposedBlocks).
  const int n = 3 * nodeCount(), c = 3 * contact_->size();
  std::vector<Eigen::Triplet<double>> bEntries, minusG, tTransposed;
  contact_->appendTransposedBlocks(bEntries, minusG, tTransposed);
  Eigen::SparseMatrix<double> b(n, c);
  b.setFromTriplets(bEntries.begin(), bEntries.end());
  Eigen::SparseMatrix<double> kMinusM = k;
  for (int d = 0; d < 3; ++d)
    for (int i = 0; i < nodeCount(); ++i)
      kMinusM.coeffRef(d * nodeCount() + i, d * nodeCount() + i) -= model_.mass[i];
  const Eigen::SparseMatrix<double> coupling = kMinusM * b;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(k.nonZeros() + coupling.nonZeros() + minusG.size() + tTransposed.size());
  auto append = [&](const Eigen::SparseMatrix<double>& block, int rowOffset, int colOffset) {
    for (int j = 0; j < block.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(block, j); it; ++it)
        entries.emplace_back(rowOffset + it.row(), colOffset + it.col(), it.value());
  };
  append(k, 0, 0);
  append(coupling, 0, n);
  for (const auto& e : minusG) entries.emplace_back(n + e.row(), e.col(), e.value());
  for (const auto& e : tTransposed) entries.emplace_back(n + e.row(), n + e.col(), e.value());
  Eigen::SparseMatrix<double> system(n + c, n + c);
  system.setFromTriplets(entries.begin(), entries.end());
  system.makeCompressed();
  return system;
}

}  // namespace weft
