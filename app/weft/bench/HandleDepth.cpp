#include "HandleDepth.h"

#include <weft/contact/HandleTargetSamples.h>

#include <algorithm>

namespace weft::cli {

bool hasHandlesAndObstacles(const Scene& scene) {
  if (scene.obstacles.empty()) return false;
  for (const Cloth& cloth : scene.cloths)
    for (const Attachment& a : cloth.attachments)
      if (a.kind == Attachment::Kind::Handle) return true;
  return false;
}

double deepestHandleTargetDepth(const Scene& scene) {
  double deepest = 0.0;
  forEachHandleTargetNearObstacle(scene, 0, 0.0, [&](const HandleTargetSample& s) {
    deepest = std::max(deepest, -s.distance);
  });
  return deepest;
}

}  // namespace weft::cli
