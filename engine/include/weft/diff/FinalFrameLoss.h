#pragma once
// Final-frame target (task.loss.final {target, vertices, weight}):
//
//   L = weight * sum_{i in V} |x_N,i - target_i|^2   (m^2),
//
// with V the listed vertices (global scene indices) or all vertices. The target is a float64
// .npy of shape [vertices, 3], or [S, vertices, 3] whose last state is used (so a positions.npy
// of a run can serve as the target).

#include <weft/diff/LossTerm.h>

#include <vector>

namespace weft {

class FinalFrameLoss final : public LossTerm {
 public:
  FinalFrameLoss(NodeMatrix target, std::vector<int> vertices, double weight);
  const char* name() const override { return "final"; }
  double value(const Trajectory& trajectory) const override;
  void addGradient(const Trajectory& trajectory, std::vector<NodeMatrix>& gradient) const override;

 private:
  NodeMatrix target_;
  std::vector<int> vertices_;
  double weight_;
};

}  // namespace weft
