#include <weft/contact/ContactObstacle.h>
#include <weft/contact/HandleObstacleCheck.h>

#include <cstdio>

namespace weft {

std::vector<std::string> handlesEnteringObstacles(const Scene& scene) {
  std::vector<std::string> messages;
  bool handles = false;
  for (const Cloth& cloth : scene.cloths)
    for (const Attachment& a : cloth.attachments) handles |= a.kind == Attachment::Kind::Handle;
  // Built only when there is something to check (a mesh obstacle's shape builds its BVH): the
  // editor runs this on every edit.
  if (!handles || scene.obstacles.empty()) return messages;
  std::vector<std::unique_ptr<ObstacleShape>> shapes;
  for (const Obstacle& o : scene.obstacles) shapes.push_back(makeObstacleShape(o));
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const Cloth& cloth = scene.cloths[c];
    for (std::size_t a = 0; a < cloth.attachments.size(); ++a) {
      const Attachment& attachment = cloth.attachments[a];
      if (attachment.kind != Attachment::Kind::Handle) continue;
      for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
        const Obstacle& obstacle = scene.obstacles[k];
        double first = -1.0, deepest = 0.0;
        for (int n = 0; n <= scene.time.steps; ++n) {
          const double t = n * scene.time.dt;
          const RigidPose pose = obstacle.motion ? poseAt(*obstacle.motion, t) : RigidPose{};
          for (int v : attachment.vertices) {
            const Vec3 target =
                attachment.trajectory.target(cloth.mesh.vertices.row(v).transpose(), t);
            SurfaceSample s;
            // Reach 0: only points inside (or on) the surface need an answer.
            if (!shapes[k]->sample(pose.inverse(target), 0.0, s) || !(s.distance < 0.0)) continue;
            if (first < 0.0) first = t;
            deepest = std::max(deepest, -s.distance);
          }
        }
        if (first < 0.0) continue;
        char what[320];
        std::snprintf(
            what, sizeof what,
            "cloths.%zu.attachments.%zu: the handle's targets enter obstacles.%zu (%s) from t = "
            "%.3g s, up to %.1f mm deep; the attachment will pull its vertices into the obstacle "
            "against the contact, and steps may not converge",
            c, a, k, shapes[k]->name(), first, 1e3 * deepest);
        messages.push_back(scene.file + ": " + what);
      }
    }
  }
  return messages;
}

}  // namespace weft
