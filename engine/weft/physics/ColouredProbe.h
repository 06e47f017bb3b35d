#pragma once
// Assembling a 3m x 3m matrix known only through its products with vectors (a matrix-free
// operator) whose 3 x 3 blocks follow a node graph: P's, where two nodes are coupled when they
// share a constraint row, which is also the pattern of Delta P and of the clamped Hessian.
// Curtis-Powell-Reid probing: with a greedy distance-2 colouring of the graph, the nodes of one
// colour share no neighbour, so one product with the sum of a colour's unit vectors (per
// coordinate) recovers all their columns: 3 x (colour count) products instead of 3m.
//
// Flat index = coordinate * m + node, the column-major storage of a NodeMatrix, so a NodeMatrix's
// data is the 3m vector the assembled matrix multiplies and its factor solves. Every entry of
// the block pattern is stored, zeros included, so the pattern (and a kept symbolic
// factorisation) never changes between assemblies.

#include <weft/core/Types.h>

#include <Eigen/SparseCore>

#include <functional>
#include <vector>

namespace weft {

class ColouredProbe {
 public:
  using Multiply = std::function<void(const NodeMatrix& in, NodeMatrix& out)>;

  // `graph`: an m x m matrix whose stored entries are the coupled node pairs.
  explicit ColouredProbe(const Eigen::SparseMatrix<double>& graph);
  int colourCount() const { return static_cast<int>(colourNodes_.size()); }

  // out = blocks (x) I_3 (when given: an m x m matrix on the graph's pattern) + scale * Op, with
  // Op known through `multiply`. The triplet and probe buffers are kept between calls.
  void assemble(const Multiply& multiply, double scale, const Eigen::SparseMatrix<double>* blocks,
                Eigen::SparseMatrix<double>& out);

 private:
  std::vector<std::vector<int>> neighbours_;  // per node, itself included, sorted
  std::vector<std::vector<int>> colourNodes_;
  std::vector<Eigen::Triplet<double>> entries_;
  NodeMatrix probe_, image_;
};

}  // namespace weft
