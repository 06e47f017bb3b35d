// The depth a step reports (StepStats::depth, stats.csv's depth): the deepest node inside any
// obstacle's contact skin, skin minus the node's signed distance, against analytic geometry.

#include <support/SceneBuilder.h>
#include <weft/contact/FrictionalContact.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

// A small cloth far above a sphere (radius 0.3 at the origin) and a ground plane at y = -1.
Scene sphereAndGround() {
  nlohmann::json doc = test::gridScene(0.2, 2, 0.01, 5);
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 2.0, 0.0}}};
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.3}}}, {"thickness", 0.002}},
      {{"plane", {{"point", {0.0, -1.0, 0.0}}, {"normal", {0.0, 1.0, 0.0}}}},
       {"thickness", 0.001}}};
  return test::parse(doc);
}

TEST(PenetrationDepth, IsTheSkinMinusTheSignedDistanceOfTheDeepestNode) {
  Simulator sim(sphereAndGround());
  const FrictionalContact& contact = *sim.contact();
  NodeMatrix x = sim.positions();
  EXPECT_EQ(contact.deepestPenetration(x), 0.0);  // every node 1.7 m above the sphere

  x.row(0) << 0.0, 0.3 + 0.0015, 0.0;  // outside the sphere, 0.5 mm inside its 2 mm skin
  EXPECT_NEAR(contact.deepestPenetration(x), 0.0005, 1e-12);
  x.row(1) << 0.0, -0.3 + 0.01, 0.0;  // 1 cm inside the sphere, through its bottom
  EXPECT_NEAR(contact.deepestPenetration(x), 0.012, 1e-12);
  x.row(2) << 5.0, -1.05, 0.0;  // 5 cm below the ground, far from the sphere
  EXPECT_NEAR(contact.deepestPenetration(x), 0.051, 1e-12);
}

TEST(PenetrationDepth, EveryStepReportsItsEndState) {
  // Dropped onto the sphere with a solve too short to stop the cloth: nodes end inside.
  nlohmann::json doc = test::gridScene(0.3, 6, 0.01, 12);
  doc["gravity"] = {0.0, -9.8, 0.0};
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 0.31, 0.0}}};
  doc["cloths"][0]["initial_velocity"] = {0.0, -3.0, 0.0};
  doc["obstacles"] = {{{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.3}}}}};
  doc["solver"] = {{"method", "pd"}, {"contact", "pd"}, {"pd_iterations", 1}, {"max_halvings", 0}};
  Simulator sim(test::parse(doc));
  double deepest = 0.0;
  for (int n = 0; n < 12; ++n) {
    const StepStats& s = sim.step();
    EXPECT_EQ(s.depth, sim.contact()->deepestPenetration(sim.positions())) << "step " << s.step;
    deepest = std::max(deepest, s.depth);
  }
  EXPECT_GT(deepest, 1e-3);  // the short solve let the cloth into the sphere, and it shows
}

}  // namespace
}  // namespace weft
