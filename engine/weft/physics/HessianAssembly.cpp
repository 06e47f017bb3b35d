#include <weft/physics/HessianAssembly.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace weft {

HessianAssembly::HessianAssembly(const Eigen::SparseMatrix<double>& system)
    : m_(static_cast<int>(system.rows())) {
  // Node j's neighbours: the rows of P's column j (P is symmetric), and j itself.
  neighbourStart_.assign(m_ + 1, 0);
  for (int j = 0; j < m_; ++j) {
    const std::size_t begin = neighbours_.size();
    bool self = false;
    for (Eigen::SparseMatrix<double>::InnerIterator it(system, j); it; ++it) {
      neighbours_.push_back(static_cast<int>(it.row()));
      self = self || it.row() == j;
    }
    if (!self) neighbours_.push_back(j);
    std::sort(neighbours_.begin() + static_cast<std::ptrdiff_t>(begin), neighbours_.end());
    neighbourStart_[j + 1] = static_cast<int>(neighbours_.size());
  }
  // Column (e, j) holds rows (d, i) for d = 0..2 and every neighbour i, sorted by flat index.
  const int n = 3 * m_;
  std::vector<int> outer(n + 1, 0);
  for (int e = 0; e < 3; ++e)
    for (int j = 0; j < m_; ++j)
      outer[e * m_ + j + 1] = 3 * (neighbourStart_[j + 1] - neighbourStart_[j]);
  for (int c = 0; c < n; ++c) outer[c + 1] += outer[c];
  pattern_.resize(n, n);
  pattern_.resizeNonZeros(outer[n]);
  std::copy(outer.begin(), outer.end(), pattern_.outerIndexPtr());
  int* inner = pattern_.innerIndexPtr();
  double* value = pattern_.valuePtr();
  Eigen::SparseMatrix<double> p = system;
  p.makeCompressed();
  for (int e = 0; e < 3; ++e)
    for (int j = 0; j < m_; ++j) {
      int k = outer[e * m_ + j];
      for (int d = 0; d < 3; ++d)
        for (int q = neighbourStart_[j]; q < neighbourStart_[j + 1]; ++q, ++k) {
          inner[k] = d * m_ + neighbours_[q];
          value[k] = d == e ? p.coeff(neighbours_[q], j) : 0.0;
        }
    }
}

int HessianAssembly::position(int i, int j, int e) const {
  const int* begin = neighbours_.data() + neighbourStart_[j];
  const int* end = neighbours_.data() + neighbourStart_[j + 1];
  const int* at = std::lower_bound(begin, end, i);
  if (at == end || *at != i)
    throw std::logic_error("HessianAssembly: element couples nodes P does not");
  return pattern_.outerIndexPtr()[e * m_ + j] + static_cast<int>(at - begin);
}

void HessianAssembly::add(const int* nodes, int count, const double* block) {
  const int size = 3 * count;
  for (int b = 0; b < count; ++b) {
    const int j = nodes[b];
    const int degree = neighbourStart_[j + 1] - neighbourStart_[j];
    for (int a = 0; a < count; ++a) {
      const int i = nodes[a];
      for (int e = 0; e < 3; ++e) {
        const int at = position(i, j, e);
        const double* column = block + static_cast<std::ptrdiff_t>(3 * b + e) * size + 3 * a;
        for (int d = 0; d < 3; ++d) values_[at + d * degree] += scale_ * column[d];
      }
    }
  }
}

void HessianAssembly::assemble(
    const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints, double scale,
    Eigen::SparseMatrix<double>& out) {
  if (out.rows() == pattern_.rows() && out.isCompressed() && out.nonZeros() == pattern_.nonZeros())
    std::memcpy(out.valuePtr(), pattern_.valuePtr(),
                sizeof(double) * static_cast<std::size_t>(out.nonZeros()));
  else
    out = pattern_;
  values_ = out.valuePtr();
  scale_ = scale;
  for (const auto& c : constraints)
    if (c->hasDerivative() && !c->derivativeBlocks(*this))
      throw std::logic_error(std::string("HessianAssembly: no derivative blocks for ") + c->name());
  values_ = nullptr;
}

}  // namespace weft
