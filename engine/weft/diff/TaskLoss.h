#pragma once
// The scene's task loss (task.loss): the sum of its terms. Built from the validated scene, with
// the targets read and checked against the scene (vertex count, step count); every problem is an
// InputError naming the JSON path of the term. Terms: "trajectory" (TrajectoryLoss), "final"
// (FinalFrameLoss), "keypoints" (KeypointLoss) and "hemline" (HemlineLoss), each with an optional
// "weight"; the loss is their sum.

#include <weft/diff/LossTerm.h>
#include <weft/scene/Scene.h>

#include <memory>
#include <vector>

namespace weft {

class TaskLoss {
 public:
  // Throws InputError if the scene has no task or a term cannot be built.
  explicit TaskLoss(const Scene& scene);

  double value(const Trajectory& trajectory) const;
  // dL/dx_n for every recorded state (zero where the loss does not look).
  std::vector<NodeMatrix> gradient(const Trajectory& trajectory) const;
  const std::vector<std::unique_ptr<LossTerm>>& terms() const { return terms_; }

 private:
  std::vector<std::unique_ptr<LossTerm>> terms_;
};

}  // namespace weft
