#pragma once
// Trajectory matching (task.loss.trajectory {target, vertices, weight}): the sum over the
// simulated states n = 1..N of the squared L2 distance to a recorded motion,
//
//   L = weight * sum_{n=1..N} sum_{i in V} |x_n,i - target_n,i|^2   (m^2, not normalised),
//
// with V the listed vertices (global scene indices, as in positions.npy) or all vertices.
// State 0 is left out: it does not depend on any parameter. The target is a float64 .npy of
// shape [S, vertices, 3] with S >= N + 1 (a positions.npy written by `weft simulate`; its state n
// is compared with state n of the run).

#include <weft/diff/LossTerm.h>

#include <vector>

namespace weft {

class TrajectoryLoss final : public LossTerm {
 public:
  // target[n] for n = 0..S-1 (each nodes x 3), vertices empty = all.
  TrajectoryLoss(std::vector<NodeMatrix> target, std::vector<int> vertices, double weight);
  const char* name() const override { return "trajectory"; }
  double value(const Trajectory& trajectory) const override;
  void addGradient(const Trajectory& trajectory, std::vector<NodeMatrix>& gradient) const override;
  int targetStates() const { return static_cast<int>(target_.size()); }

 private:
  std::vector<NodeMatrix> target_;
  std::vector<int> vertices_;
  double weight_;
};

}  // namespace weft
