#pragma once
// What the verbs that load a scene print before running it: the loader's warnings (repaired or
// suspicious input) and the checks that need the engine (handles driven into obstacles).

#include <weft/scene/Scene.h>

namespace weft::cli {

void printSceneWarnings(const Scene& scene);

}  // namespace weft::cli
