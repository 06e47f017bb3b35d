#pragma once
// A penalty on handle targets that pass into an obstacle (task.loss.handle_clearance {weight,
// margin}), for tasks whose handles stand for a manipulator's end effectors (the Sock):
//
//   L = weight * sum_{n=1..N} h * sum_{handle vertices j} max(0, margin - d(x_hat_j(t_n)))^2,
//
// with d the signed distance of vertex j's target to each obstacle's surface at t_n (negative
// inside; the obstacle's pose at t_n for a moving one) and h the step: a time integral (m^2 s,
// weight in 1/s), so the term does not change with the step count at the same motion.
//
// Why: the keypoint loss of DiffCloth's Sock (Eq. 33) looks at cloth vertices only, so a path
// that drives a handle through the foot lowers it as well as one that goes round; the spring then
// pulls the cloth into the body against the contact (HandleObstacleCheck.h), a motion no
// manipulator can make. Every optimiser found such paths (docs/applications.md, "The Sock").
//
// The term depends on the parameters directly, not on the simulated states: its value is read
// from the evaluated scene and its gradient goes straight to the handle parameters. A target
// x_hat_j(t) = R(t) rest_j + offset(t) is linear in the trajectory's knot values
// (HandleTrajectory::controlWeight), and dd/dx_hat = the surface normal, so for a Hermite point or
// tangent component c of knot P,
//
//   dL/dtheta = -2 weight sum_n h sum_j max(0, margin - d) n_c * controlWeight(t_n, control, P).

#include <weft/diff/SceneParameter.h>
#include <weft/scene/Scene.h>

#include <Eigen/Core>

#include <vector>

namespace weft {

class HandleClearanceLoss {
 public:
  HandleClearanceLoss(double weight, double margin) : weight_(weight), margin_(margin) {}
  const char* name() const { return "handle_clearance"; }
  double weight() const { return weight_; }
  double margin() const { return margin_; }

  // Of the evaluated scene (its parameters set): the penalty over its handles and obstacles.
  double value(const Scene& scene) const;
  // gradient[k] += dL/dtheta_k for each handle offset or tangent parameter (zero for the rest).
  void addParameterGradient(const Scene& scene, const std::vector<SceneParameter>& parameters,
                            Eigen::VectorXd& gradient) const;

 private:
  double weight_, margin_;
};

}  // namespace weft
