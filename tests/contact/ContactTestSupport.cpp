#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>

#include <cmath>
#include <sstream>

namespace weft::test {

nlohmann::json clothScene(double size, int quads, const Vec3& centre, double dt, double stretch,
                          double bend, double density) {
  nlohmann::json scene = gridScene(size, quads, dt, 0, stretch, bend, density);
  scene["gravity"] = {0.0, -9.8, 0.0};
  scene["solver"] = {{"pd_iterations", 400}, {"pd_tolerance", 1e-3}};
  scene["cloths"][0]["mesh"]["transform"] = {{"translate", {centre.x(), centre.y(), centre.z()}}};
  return scene;
}

void addObstacle(nlohmann::json& scene, const std::string& shape, const nlohmann::json& geometry,
                 double friction) {
  scene["obstacles"].push_back({{shape, geometry}, {"friction", friction}});
}

ContactRun runScene(const nlohmann::json& document, int steps) {
  ContactRun run;
  run.scene = std::make_unique<Scene>(parse(document));
  run.sim = std::make_unique<Simulator>(*run.scene);
  run.sim->run(steps, run.trajectory);
  return run;
}

std::string branchViolation(const ContactPoint& p, double tolerance) {
  std::ostringstream why;
  const Vec3& n = p.normal;
  const double rN = p.impulse.dot(n);
  const Vec3 rT = p.impulse - rN * n;
  const double uN = p.velocity.dot(n);
  const Vec3 uT = p.velocity - uN * n;
  // Momentum scale of the contact: what the law saw (d = m u - r) or what it applied.
  const double scale = std::max({p.effectiveMass * p.velocity.norm(), p.impulse.norm(),
                                 (p.effectiveMass * p.velocity - p.impulse).norm(), 1e-300});
  const double tol = tolerance * scale + 1e-15, velTol = tol / p.effectiveMass;
  if (std::abs(n.norm() - 1.0) > 1e-9) why << "normal not unit; ";
  if (rN < -tol) why << "r_N = " << rN << " < 0; ";
  if (rT.norm() > p.friction * rN + tol)
    why << "|r_T| = " << rT.norm() << " > mu r_N = " << p.friction * rN << "; ";
  switch (p.branch) {
    case ContactBranch::TakeOff:
      if (p.impulse.norm() > tol) why << "take-off with r = " << p.impulse.norm() << "; ";
      if (uN < -velTol) why << "take-off with u_N = " << uN << " < 0; ";
      break;
    case ContactBranch::Stick:
      if (p.velocity.norm() > velTol) why << "stick with |u| = " << p.velocity.norm() << "; ";
      break;
    case ContactBranch::Slip: {
      if (std::abs(uN) > velTol) why << "slip with u_N = " << uN << "; ";
      // At the stick-slip boundary u_T may vanish: then r_T need only lie on the cone.
      if (uT.norm() <= velTol) {
        if (std::abs(rT.norm() - p.friction * rN) > tol)
          why << "slip with r_T inside the cone and u_T = 0; ";
        break;
      }
      const Vec3 expected = -p.friction * rN * uT.normalized();
      if ((rT - expected).norm() > tol)
        why << "slip with r_T off the cone or not opposite u_T (" << (rT - expected).norm()
            << "); ";
      break;
    }
    default:
      why << "no branch; ";
  }
  return why.str();
}

}  // namespace weft::test
