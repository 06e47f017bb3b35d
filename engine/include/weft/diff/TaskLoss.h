#pragma once
// The scene's task loss (task.loss): the sum of its terms. Built from the validated scene, with
// the targets read and checked against the scene (vertex count, step count); every problem is an
// InputError naming the JSON path of the term. Terms: "trajectory" (TrajectoryLoss), "final"
// (FinalFrameLoss), "keypoints" (KeypointLoss) and "hemline" (HemlineLoss), each with an optional
// "weight", are functions of the recorded states; "handle_clearance" (HandleClearanceLoss) is a
// function of the scene's handle parameters alone. The loss is their sum.

#include <weft/diff/HandleClearanceLoss.h>
#include <weft/diff/LossTerm.h>
#include <weft/scene/Scene.h>

#include <memory>
#include <optional>
#include <vector>

namespace weft {

class TaskLoss {
 public:
  // Throws InputError if the scene has no task or a term cannot be built.
  explicit TaskLoss(const Scene& scene);

  // The loss of `trajectory`, recorded from `scene` (the scene with the evaluated parameter
  // values: the clearance term reads its handles).
  double value(const Scene& scene, const Trajectory& trajectory) const;
  // dL/dx_n for every recorded state (zero where the loss does not look).
  std::vector<NodeMatrix> gradient(const Trajectory& trajectory) const;
  // gradient[k] += the partial dL/dtheta_k of the terms that depend on parameters directly (the
  // clearance term); what flows through the states is the adjoint's (Backpropagation).
  void addParameterGradient(const Scene& scene, const std::vector<SceneParameter>& parameters,
                            Eigen::VectorXd& gradient) const;
  // The terms of the recorded states.
  const std::vector<std::unique_ptr<LossTerm>>& terms() const { return terms_; }
  const std::optional<HandleClearanceLoss>& clearance() const { return clearance_; }

 private:
  std::vector<std::unique_ptr<LossTerm>> terms_;
  std::optional<HandleClearanceLoss> clearance_;
};

}  // namespace weft
