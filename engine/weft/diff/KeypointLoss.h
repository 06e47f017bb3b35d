#pragma once
// Keypoint targets at chosen steps (task.loss.keypoints {points, weight}; DiffCloth Appendix B,
// Sock, Eq. 33: sock vertices matched to points on the foot at the middle and the end of the
// run):
//
//   L = weight * sum_k w_k |x_{n_k, i_k} - target_k|^2   (m^2),
//
// one entry k per (state n_k, global vertex i_k, target position, per-entry weight w_k). Squared
// distances, where Eq. 33 sums plain distances: the square is smooth where a keypoint reaches its
// target, which a gradient-based optimiser and a finite-difference check both need.

#include <weft/diff/LossTerm.h>

#include <vector>

namespace weft {

class KeypointLoss final : public LossTerm {
 public:
  struct Keypoint {
    int state = 0;   // state index n (0..N)
    int vertex = 0;  // global vertex index (scene order)
    Vec3 target = Vec3::Zero();
    double weight = 1.0;
  };
  KeypointLoss(std::vector<Keypoint> keypoints, double weight);
  const char* name() const override { return "keypoints"; }
  double value(const Trajectory& trajectory) const override;
  void addGradient(const Trajectory& trajectory, std::vector<NodeMatrix>& gradient) const override;
  const std::vector<Keypoint>& keypoints() const { return keypoints_; }

 private:
  std::vector<Keypoint> keypoints_;
  double weight_;
};

}  // namespace weft
