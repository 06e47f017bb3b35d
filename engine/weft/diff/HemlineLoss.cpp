#include <weft/diff/HemlineLoss.h>

#include <cmath>

namespace weft {

double targetHemlineHeight(double apexAngleDeg, double apexHeight, double slantLength) {
  return apexHeight - slantLength * std::cos(0.5 * apexAngleDeg * M_PI / 180.0);
}

HemlineLoss::HemlineLoss(std::vector<int> vertices, std::vector<int> states, const Vec3& up,
                         double height, double weight)
    : vertices_(std::move(vertices)),
      states_(std::move(states)),
      up_(up),
      height_(height),
      weight_(weight) {}

double HemlineLoss::value(const Trajectory& trajectory) const {
  double sum = 0.0;
  for (int n : states_) {
    const NodeMatrix& x = trajectory.positions.at(n);
    for (int i : vertices_) {
      const double gap = x.row(i).dot(up_.transpose()) - height_;
      sum += gap * gap;
    }
  }
  return weight_ * sum / static_cast<double>(vertices_.size());
}

void HemlineLoss::addGradient(const Trajectory& trajectory,
                              std::vector<NodeMatrix>& gradient) const {
  const double scale = 2.0 * weight_ / static_cast<double>(vertices_.size());
  for (int n : states_) {
    const NodeMatrix& x = trajectory.positions.at(n);
    for (int i : vertices_) {
      const double gap = x.row(i).dot(up_.transpose()) - height_;
      gradient.at(n).row(i) += scale * gap * up_.transpose();
    }
  }
}

}  // namespace weft
