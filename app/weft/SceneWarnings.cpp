#include "SceneWarnings.h"

#include <weft/contact/HandleObstacleCheck.h>

#include <cstdio>

namespace weft::cli {

void printSceneWarnings(const Scene& scene) {
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  for (const std::string& w : handlesEnteringObstacles(scene))
    std::fprintf(stderr, "warning: %s\n", w.c_str());
}

}  // namespace weft::cli
