#include <weft/physics/ProjectiveConstraint.h>

namespace weft {

void ProjectiveConstraint::setSelection(
    int nodes, const std::vector<Eigen::Triplet<double>>& rowNodeCoefficients) {
  std::vector<Eigen::Triplet<double>> transposed;
  transposed.reserve(rowNodeCoefficients.size());
  for (const auto& t : rowNodeCoefficients) transposed.emplace_back(t.col(), t.row(), t.value());
  at_.resize(nodes, rowCount());
  at_.setFromTriplets(transposed.begin(), transposed.end());
  at_.makeCompressed();
}

double ProjectiveConstraint::energy(const NodeMatrix& x) const {
  NodeMatrix scratch(rowCount(), 3);
  return project(x, scratch);
}

void ProjectiveConstraint::gather(const NodeMatrix& wp, double scale, NodeMatrix& out) const {
  const int nodes = static_cast<int>(at_.rows());
  const int* outer = at_.outerIndexPtr();
  const int* inner = at_.innerIndexPtr();
  const double* value = at_.valuePtr();
  const double *px = wp.col(0).data(), *py = wp.col(1).data(), *pz = wp.col(2).data();
  double *ox = out.col(0).data(), *oy = out.col(1).data(), *oz = out.col(2).data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nodes; ++i) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int r = inner[k];
      const double a = value[k];
      sx += a * px[r], sy += a * py[r], sz += a * pz[r];
    }
    ox[i] += scale * sx, oy[i] += scale * sy, oz[i] += scale * sz;
  }
}

Eigen::SparseMatrix<double> ProjectiveConstraint::weightedGram() const {
  const Eigen::SparseMatrix<double> a = at_.transpose();
  return Eigen::SparseMatrix<double>(at_ * weights_.asDiagonal() * a);
}

Eigen::SparseMatrix<double> assembleSystemMatrix(
    const Eigen::VectorXd& mass,
    const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints, double h) {
  const int m = static_cast<int>(mass.size());
  Eigen::SparseMatrix<double> system(m, m);
  std::vector<Eigen::Triplet<double>> diagonal;
  diagonal.reserve(m);
  for (int i = 0; i < m; ++i) diagonal.emplace_back(i, i, mass[i]);
  system.setFromTriplets(diagonal.begin(), diagonal.end());
  for (const auto& c : constraints) system += (h * h) * c->weightedGram();
  system.makeCompressed();
  return system;
}

}  // namespace weft
