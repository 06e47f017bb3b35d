// The experimental active-set Newton contact solve (solver.contact = "active_set",
// ActiveContactSet.h) on the sphere drop that the PD contact solve does not converge: iterates
// are projected onto the contact constraints, so no node ends any step inside the sphere's
// skin, converged or not, and every contact of a converged step obeys its branch.

#include "ContactTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

constexpr double kRadius = 0.4, kSkin = 1e-3;
// The constraint holds on the tangent plane frozen at detection; a node sliding over the curved
// surface during the step can dip below the sphere by about travel^2 / (2 R): 1 mm at these speeds.
constexpr double kPenetrationTolerance = 1e-3;

TEST(ActiveSetContact, SphereDropNeverPenetratesAndConvergedStepsObeyTheLaw) {
  nlohmann::json doc =
      test::clothScene(0.8, 12, Vec3(0.0, kRadius + 0.05, 0.0), 0.01, 500.0, 1e-3, 0.2);
  test::addObstacle(doc, "sphere", {{"center", {0, 0, 0}}, {"radius", kRadius}}, 0.5);
  doc["obstacles"][0]["thickness"] = kSkin;
  doc["solver"]["contact"] = "active_set";
  const test::ContactRun run = test::runScene(doc, 60);
  const Trajectory& t = run.trajectory;
  int converged = 0, checked = 0, activeContacts = 0;
  for (int n = 1; n <= t.stepCount(); ++n) {
    ASSERT_TRUE(t.positions[n].allFinite());
    const double deepest = t.positions[n].rowwise().norm().minCoeff() - kRadius - kSkin;
    ASSERT_GT(deepest, -kPenetrationTolerance)
        << "step " << n << ", converged " << t.steps[n - 1].converged;
    if (!t.steps[n - 1].converged) continue;
    ++converged;
    for (const ContactPoint& p : t.contacts[n - 1].points) {
      // The law holds to the solver's own tolerance: pd_tolerance * h as a velocity, relative
      // to the contact's momentum scale.
      ASSERT_EQ(test::branchViolation(p, 1e-3), "")
          << "step " << n << " node " << p.node << " " << branchName(p.branch);
      ++checked;
      activeContacts += p.branch != ContactBranch::TakeOff;
    }
  }
  RecordProperty("converged_steps", std::to_string(converged));
  EXPECT_GT(activeContacts, 0) << "no converged step had an active contact";
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace weft
