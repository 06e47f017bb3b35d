#include <weft/diff/TrajectoryLoss.h>

#include <algorithm>

namespace weft {

TrajectoryLoss::TrajectoryLoss(std::vector<NodeMatrix> target, std::vector<int> vertices,
                               double weight)
    : target_(std::move(target)), vertices_(std::move(vertices)), weight_(weight) {}

double TrajectoryLoss::value(const Trajectory& trajectory) const {
  double sum = 0.0;
  const int states = std::min(static_cast<int>(trajectory.positions.size()), targetStates());
  for (int n = 1; n < states; ++n) {
    const NodeMatrix& x = trajectory.positions[n];
    if (vertices_.empty()) {
      sum += (x - target_[n]).squaredNorm();
    } else {
      for (int v : vertices_) sum += (x.row(v) - target_[n].row(v)).squaredNorm();
    }
  }
  return weight_ * sum;
}

void TrajectoryLoss::addGradient(const Trajectory& trajectory,
                                 std::vector<NodeMatrix>& gradient) const {
  const int states = std::min(static_cast<int>(trajectory.positions.size()), targetStates());
  for (int n = 1; n < states; ++n) {
    const NodeMatrix& x = trajectory.positions[n];
    if (vertices_.empty()) {
      gradient[n] += 2.0 * weight_ * (x - target_[n]);
    } else {
      for (int v : vertices_) gradient[n].row(v) += 2.0 * weight_ * (x.row(v) - target_[n].row(v));
    }
  }
}

}  // namespace weft
