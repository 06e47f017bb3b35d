#include <weft/contact/ContactObstacle.h>
#include <weft/contact/HandleTargetSamples.h>

#include <memory>

namespace weft {

bool hasHandlesAndObstacles(const Scene& scene) {
  if (scene.obstacles.empty()) return false;
  for (const Cloth& cloth : scene.cloths)
    for (const Attachment& a : cloth.attachments)
      if (a.kind == Attachment::Kind::Handle) return true;
  return false;
}

void forEachHandleTargetNearObstacle(const Scene& scene, int firstStep, double reach,
                                     const std::function<void(const HandleTargetSample&)>& visit) {
  // Built only when there is something to sample (a mesh obstacle's shape builds its BVH): the
  // editor checks handles on every edit.
  if (!hasHandlesAndObstacles(scene)) return;
  std::vector<std::unique_ptr<ObstacleShape>> shapes;
  for (const Obstacle& o : scene.obstacles) shapes.push_back(makeObstacleShape(o));
  HandleTargetSample sample;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const Cloth& cloth = scene.cloths[c];
    for (std::size_t a = 0; a < cloth.attachments.size(); ++a) {
      const Attachment& attachment = cloth.attachments[a];
      if (attachment.kind != Attachment::Kind::Handle) continue;
      for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
        const Obstacle& obstacle = scene.obstacles[k];
        for (int n = firstStep; n <= scene.time.steps; ++n) {
          const double t = n * scene.time.dt;
          const RigidPose pose = obstacle.motion ? poseAt(*obstacle.motion, t) : RigidPose{};
          for (int v : attachment.vertices) {
            const Vec3 target =
                attachment.trajectory.target(cloth.mesh.vertices.row(v).transpose(), t);
            SurfaceSample s;
            if (!shapes[k]->sample(pose.inverse(target), reach, s) || !(s.distance < reach))
              continue;
            sample.cloth = static_cast<int>(c);
            sample.attachment = static_cast<int>(a);
            sample.obstacle = static_cast<int>(k);
            sample.time = t;
            sample.distance = s.distance;
            sample.normal = pose.rotation * s.normal;
            sample.shape = shapes[k]->name();
            visit(sample);
          }
        }
      }
    }
  }
}

}  // namespace weft
