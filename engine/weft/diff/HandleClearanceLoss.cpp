#include <weft/diff/HandleClearanceLoss.h>

#include <weft/contact/HandleTargetSamples.h>

namespace weft {

double HandleClearanceLoss::value(const Scene& scene) const {
  double sum = 0.0;
  // The targets at each step's end time, t_1..t_N: where AttachmentConstraint pulls in a step.
  forEachHandleTargetNearObstacle(scene, 1, margin_, [&](const HandleTargetSample& s) {
    const double penetration = margin_ - s.distance;
    sum += penetration * penetration;
  });
  return weight_ * scene.time.dt * sum;
}

void HandleClearanceLoss::addParameterGradient(const Scene& scene,
                                               const std::vector<SceneParameter>& parameters,
                                               Eigen::VectorXd& gradient) const {
  using Kind = SceneParameter::Kind;
  bool any = false;
  for (const SceneParameter& p : parameters)
    any |= p.kind == Kind::HandleOffset || p.kind == Kind::HandleTangent;
  if (!any) return;
  const double scale = -2.0 * weight_ * scene.time.dt;
  forEachHandleTargetNearObstacle(scene, 1, margin_, [&](const HandleTargetSample& s) {
    const double penetration = margin_ - s.distance;
    const HandleTrajectory& trajectory = scene.cloths[static_cast<std::size_t>(s.cloth)]
                                             .attachments[static_cast<std::size_t>(s.attachment)]
                                             .trajectory;
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      const SceneParameter& p = parameters[k];
      if ((p.kind != Kind::HandleOffset && p.kind != Kind::HandleTangent) || p.cloth != s.cloth ||
          p.index != s.attachment)
        continue;
      const auto control = p.kind == Kind::HandleOffset ? HandleTrajectory::Control::Offset
                                                        : HandleTrajectory::Control::Tangent;
      const double weight = trajectory.controlWeight(s.time, control, p.knot);
      gradient[static_cast<int>(k)] += scale * penetration * s.normal[p.component] * weight;
    }
  });
}

}  // namespace weft
