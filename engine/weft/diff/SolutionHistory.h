#pragma once
// A starting point for one backward step's iterative solve K_n z = g_n from the steps solved
// before it: z0 = Z c with c minimising |g_n - W c|, where Z holds the last `capacity`
// solutions and W their products with K, each taken with the K of the step it solved (so
// W z_i = g_i up to that solve's residual: no product is spent on the guess). This is the
// projection onto previous solutions for sequences of systems with successive right-hand sides
// (Fischer, "Projection techniques for iterative solution of Ax = b with successive right-hand
// sides", 1998), here with a matrix that changes slowly along the trajectory; the guess only has
// to be good: the solver measures its true residual and iterates from there.
//
// Why it pays: a backward pass walks one trajectory, so consecutive adjoints share their slow
// components (the soft modes P models worst), and a few previous solutions span much of what
// the warm start from the last one alone misses (docs/benchmarks.md, "Previous solutions").

#include <weft/core/Types.h>

#include <Eigen/Dense>

#include <algorithm>
#include <vector>

namespace weft {

class SolutionHistory {
 public:
  explicit SolutionHistory(int capacity) : capacity_(std::max(0, capacity)) {}
  int capacity() const { return capacity_; }
  int size() const { return size_; }
  void clear() { size_ = 0; }

  // Keeps z (a step's solution) with its product K z; the oldest pair drops out when full.
  // Zero or non-finite pairs are not kept.
  void add(const NodeMatrix& z, const NodeMatrix& product);
  // z = the combination of the kept solutions whose products best match rhs (least squares);
  // false, z untouched, when nothing is kept or nothing matches.
  bool guess(const NodeMatrix& rhs, NodeMatrix& z) const;

 private:
  int capacity_;
  int size_ = 0;
  std::vector<NodeMatrix> solutions_, products_;  // Z and W, newest first
  Eigen::MatrixXd gram_;                          // W^T W
};

}  // namespace weft
