#pragma once
// How far a task's handles go into its obstacles, for the table of where each optimiser run's
// answer puts them (ApplicationsBench): the engine's walk over handle targets near obstacles
// (contact/HandleTargetSamples.h), reduced to one number.

#include <weft/contact/HandleTargetSamples.h>
#include <weft/scene/Scene.h>

namespace weft::bench {

// The deepest any handle vertex's target goes inside an obstacle (m, its skin not counted), at
// every step's end time, the samples the scene check for handles entering obstacles
// (contact/HandleObstacleCheck.h) warns from; 0 when none enters.
double deepestHandleTargetDepth(const Scene& scene);

}  // namespace weft::bench
