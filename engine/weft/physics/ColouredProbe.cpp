#include <weft/physics/ColouredProbe.h>

#include <algorithm>

namespace weft {

ColouredProbe::ColouredProbe(const Eigen::SparseMatrix<double>& graph) {
  const int m = static_cast<int>(graph.rows());
  neighbours_.assign(m, {});
  for (int i = 0; i < m; ++i) neighbours_[i].push_back(i);
  for (int j = 0; j < graph.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(graph, j); it; ++it)
      if (it.row() != j) {
        neighbours_[j].push_back(static_cast<int>(it.row()));
        neighbours_[it.row()].push_back(j);
      }
  for (auto& list : neighbours_) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  // Greedy distance-2 colouring in node order: a node's colour differs from every coloured node
  // within two hops (mark[c] == i: colour c is taken for node i).
  std::vector<int> colour(m, -1), mark;
  for (int i = 0; i < m; ++i) {
    for (int j : neighbours_[i])
      for (int k : neighbours_[j])
        if (colour[k] >= 0) {
          if (static_cast<int>(mark.size()) <= colour[k]) mark.resize(colour[k] + 1, -1);
          mark[colour[k]] = i;
        }
    int c = 0;
    while (c < static_cast<int>(mark.size()) && mark[c] == i) ++c;
    colour[i] = c;
    if (static_cast<int>(colourNodes_.size()) <= c) colourNodes_.resize(c + 1);
    colourNodes_[c].push_back(i);
  }
}

void ColouredProbe::assemble(const Multiply& multiply, double scale,
                             const Eigen::SparseMatrix<double>* blocks,
                             Eigen::SparseMatrix<double>& out) {
  const int m = static_cast<int>(neighbours_.size());
  entries_.clear();
  if (blocks)
    for (int k = 0; k < blocks->outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*blocks, k); it; ++it)
        for (int d = 0; d < 3; ++d)
          entries_.emplace_back(d * m + it.row(), d * m + it.col(), it.value());
  probe_.setZero(m, 3);
  image_.resize(m, 3);
  for (const std::vector<int>& nodes : colourNodes_)
    for (int d = 0; d < 3; ++d) {
      for (int i : nodes) probe_(i, d) = 1.0;
      multiply(probe_, image_);
      for (int i : nodes) probe_(i, d) = 0.0;
      // Column (d, i) lives on i's neighbours, which see no other node of this colour.
      for (int i : nodes)
        for (int j : neighbours_[i])
          for (int e = 0; e < 3; ++e)
            entries_.emplace_back(e * m + j, d * m + i, scale * image_(j, e));
    }
  out.resize(3 * m, 3 * m);
  out.setFromTriplets(entries_.begin(), entries_.end());
  out.makeCompressed();
}

}  // namespace weft
