#include "HandleDepth.h"

#include <weft/contact/HandleTargetSamples.h>

#include <algorithm>

namespace weft::bench {

double deepestHandleTargetDepth(const Scene& scene) {
  double deepest = 0.0;
  forEachHandleTargetNearObstacle(scene, 0, 0.0, [&](const HandleTargetSample& s) {
    deepest = std::max(deepest, -s.distance);
  });
  return deepest;
}

}  // namespace weft::bench
