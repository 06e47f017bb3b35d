#include <weft/diff/HandleClearanceLoss.h>

#include <weft/contact/ContactObstacle.h>

#include <memory>

namespace weft {

template <class Visit>
void HandleClearanceLoss::forEachPenetration(const Scene& scene, Visit&& visit) const {
  std::vector<std::unique_ptr<ObstacleShape>> shapes;
  for (const Obstacle& o : scene.obstacles) shapes.push_back(makeObstacleShape(o));
  const double h = scene.time.dt;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const Cloth& cloth = scene.cloths[c];
    for (std::size_t a = 0; a < cloth.attachments.size(); ++a) {
      const Attachment& attachment = cloth.attachments[a];
      if (attachment.kind != Attachment::Kind::Handle) continue;
      for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
        const Obstacle& obstacle = scene.obstacles[k];
        // The targets at each step's end time: where AttachmentConstraint pulls during step n.
        for (int n = 1; n <= scene.time.steps; ++n) {
          const double t = n * h;
          const RigidPose pose = obstacle.motion ? poseAt(*obstacle.motion, t) : RigidPose{};
          for (int v : attachment.vertices) {
            const Vec3 target =
                attachment.trajectory.target(cloth.mesh.vertices.row(v).transpose(), t);
            SurfaceSample s;
            if (!shapes[k]->sample(pose.inverse(target), margin_, s)) continue;
            const double penetration = margin_ - s.distance;
            if (!(penetration > 0.0)) continue;
            visit(static_cast<int>(c), static_cast<int>(a), t, penetration,
                  Vec3(pose.rotation * s.normal));
          }
        }
      }
    }
  }
}

double HandleClearanceLoss::value(const Scene& scene) const {
  double sum = 0.0;
  forEachPenetration(scene, [&](int, int, double, double penetration, const Vec3&) {
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
  forEachPenetration(
      scene, [&](int cloth, int attachment, double t, double penetration, const Vec3& normal) {
        const HandleTrajectory& trajectory = scene.cloths[cloth].attachments[attachment].trajectory;
        for (std::size_t k = 0; k < parameters.size(); ++k) {
          const SceneParameter& p = parameters[k];
          if ((p.kind != Kind::HandleOffset && p.kind != Kind::HandleTangent) || p.cloth != cloth ||
              p.index != attachment)
            continue;
          const auto control = p.kind == Kind::HandleOffset ? HandleTrajectory::Control::Offset
                                                            : HandleTrajectory::Control::Tangent;
          const double weight = trajectory.controlWeight(t, control, p.knot);
          gradient[static_cast<int>(k)] += scale * penetration * normal[p.component] * weight;
        }
      });
}

}  // namespace weft
