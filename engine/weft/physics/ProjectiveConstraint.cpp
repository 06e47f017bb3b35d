#include <weft/physics/ProjectiveConstraint.h>

namespace weft {

void ProjectiveConstraint::setSelection(int nodes,
                                        const std::vector<Eigen::Triplet<double>>& rowNodeCoefficients) {
  std::vector<Eigen::Triplet<double>> transposed;
  transposed.reserve(rowNodeCoefficients.size());
  for (const auto& t : rowNodeCoefficients) transposed.emplace_back(t.col(), t.row(), t.value());
  at_.resize(nodes, rowCount());
  at_.setFromTriplets(transposed.begin(), transposed.end());
}

Eigen::SparseMatrix<double> ProjectiveConstraint::weightedGram() const {
  const Eigen::SparseMatrix<double> a = at_.transpose();
  return Eigen::SparseMatrix<double>(at_ * weights_.asDiagonal() * a);
}

}  // namespace weft
