#pragma once
// Handles whose targets pass inside an obstacle. The attachment's spring then pulls its vertices
// into the obstacle while the contact holds them on its skin: a stiff spring stretched by
// centimetres against grams of cloth, whose accelerations are so large that the steps cannot meet
// an absolute solver tolerance (solver.pd_tolerance, m/s^2) in double precision. Found before
// simulating, so the user is told why, not just that steps did not converge.

#include <weft/scene/Scene.h>

#include <string>
#include <vector>

namespace weft {

// One message, "<scene file>: <attachment path>: <what>" as the loader's warnings are, per
// (cloth, attachment, obstacle) whose handle targets, sampled at every step's
// end time, go deeper than the obstacle's surface (its skin not counted): the first time and the
// deepest depth. Static and moving obstacles (at the same time) alike.
std::vector<std::string> handlesEnteringObstacles(const Scene& scene);

}  // namespace weft
