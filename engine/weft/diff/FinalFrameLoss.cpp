#include <weft/diff/FinalFrameLoss.h>

namespace weft {

FinalFrameLoss::FinalFrameLoss(NodeMatrix target, std::vector<int> vertices, double weight)
    : target_(std::move(target)), vertices_(std::move(vertices)), weight_(weight) {}

double FinalFrameLoss::value(const Trajectory& trajectory) const {
  const NodeMatrix& x = trajectory.positions.back();
  if (vertices_.empty()) return weight_ * (x - target_).squaredNorm();
  double sum = 0.0;
  for (int v : vertices_) sum += (x.row(v) - target_.row(v)).squaredNorm();
  return weight_ * sum;
}

void FinalFrameLoss::addGradient(const Trajectory& trajectory,
                                 std::vector<NodeMatrix>& gradient) const {
  const NodeMatrix& x = trajectory.positions.back();
  NodeMatrix& g = gradient.back();
  if (vertices_.empty()) {
    g += 2.0 * weight_ * (x - target_);
  } else {
    for (int v : vertices_) g.row(v) += 2.0 * weight_ * (x.row(v) - target_.row(v));
  }
}

}  // namespace weft
