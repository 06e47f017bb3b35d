#pragma once
// Shared pieces of the contact tests: scene documents with obstacles, running a scene while
// keeping its per-step contact record, and the check that a recorded contact obeys the branch of
// the Signorini-Coulomb law (DiffCloth Eq. 8) it claims.

#include <weft/physics/Simulator.h>
#include <weft/record/ContactPoint.h>
#include <weft/record/Trajectory.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <string>

namespace weft::test {

// A flat square grid cloth (XZ plane, normal +Y) of `size` m with `quads` x `quads` quads,
// centred at `centre`, gravity -9.8 Y, plain contact-scene solver settings.
nlohmann::json clothScene(double size, int quads, const Vec3& centre, double dt,
                          double stretch = 1000.0, double bend = 1e-3, double density = 0.2);

// Appends an obstacle entry {shape: geometry, friction: mu}.
void addObstacle(nlohmann::json& scene, const std::string& shape, const nlohmann::json& geometry,
                 double friction);

// A scene, its simulator and the trajectory of a run (the Scene must outlive the Simulator).
struct ContactRun {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<Simulator> sim;
  Trajectory trajectory;
};
ContactRun runScene(const nlohmann::json& document, int steps);

// Empty when `p` satisfies its claimed branch within `tolerance` (relative to the contact's
// momentum scale); otherwise what is violated. Checks r_N >= 0 and |r_T| <= mu r_N always, and
// per branch: take-off r = 0 and u_N >= 0; stick u = 0; slip u_N = 0, r_T = -mu r_N u_T/|u_T|.
std::string branchViolation(const ContactPoint& p, double tolerance = 1e-9);

}  // namespace weft::test

namespace weft::test {
inline double maxSpeedOf(const NodeMatrix& v) {
  return std::sqrt(v.rowwise().squaredNorm().maxCoeff());
}
}  // namespace weft::test
