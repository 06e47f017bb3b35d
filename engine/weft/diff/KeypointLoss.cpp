#include <weft/diff/KeypointLoss.h>

namespace weft {

KeypointLoss::KeypointLoss(std::vector<Keypoint> keypoints, double weight)
    : keypoints_(std::move(keypoints)), weight_(weight) {}

double KeypointLoss::value(const Trajectory& trajectory) const {
  double sum = 0.0;
  for (const Keypoint& k : keypoints_) {
    const Vec3 x = trajectory.positions.at(k.state).row(k.vertex).transpose();
    sum += k.weight * (x - k.target).squaredNorm();
  }
  return weight_ * sum;
}

void KeypointLoss::addGradient(const Trajectory& trajectory,
                               std::vector<NodeMatrix>& gradient) const {
  for (const Keypoint& k : keypoints_) {
    const Vec3 x = trajectory.positions.at(k.state).row(k.vertex).transpose();
    gradient.at(k.state).row(k.vertex) += (2.0 * weight_ * k.weight * (x - k.target)).transpose();
  }
}

}  // namespace weft
