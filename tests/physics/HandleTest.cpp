// Handles (moving attachments) drag their vertices along the trajectory, within the
// stretch of the attachment spring; fixed attachments hold their vertices in place.

#include "PhysicsTestSupport.h"

#include <support/SceneBuilder.h>

#include <gtest/gtest.h>

#include <algorithm>

namespace weft {
namespace {

constexpr int kQuads = 4;
constexpr double kSize = 0.4, kDensity = 0.1, kStiffness = 1e4;

// The spring's stretch if it alone carried the whole cloth at a few g: a generous physical
// bound for how far a pinned vertex may lag its target.
double springTolerance() {
  return 5.0 * kDensity * kSize * kSize * 9.8 / kStiffness;
}

class Handle : public ::testing::TestWithParam<std::string> {};

TEST_P(Handle, KeyframedCornersFollowTheirTrajectory) {
  nlohmann::json doc = test::hangingClothScene(kSize, kQuads, 0.01, 0, 300.0, 1e-3, kDensity);
  doc["solver"]["method"] = GetParam();
  // Both top corners slide 0.3 m along +X during [0.2, 1.0] s, then hold.
  doc["cloths"][0]["attachments"] = {
      {{"vertices", {0, kQuads}},
       {"kind", "handle"},
       {"stiffness", kStiffness},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.2}, {"offset", {0, 0, 0}}}, {{"time", 1.0}, {"offset", {0.3, 0, 0}}}}}}}}};
  const Scene scene = test::parse(doc);
  Simulator sim(scene);
  const HandleTrajectory& trajectory = scene.cloths[0].attachments[0].trajectory;
  const NodeMatrix rest = sim.positions();
  double worst = 0.0;
  for (int n = 1; n <= 180; ++n) {
    sim.step();
    for (int v : {0, kQuads}) {
      const Vec3 target = trajectory.target(rest.row(v).transpose(), sim.time());
      worst = std::max(worst, (sim.positions().row(v).transpose() - target).norm());
    }
  }
  RecordProperty("max_lag_m", std::to_string(worst));
  EXPECT_LT(worst, springTolerance());
  // The handles really moved, and the cloth came along with them.
  EXPECT_NEAR(sim.positions()(0, 0) - rest(0, 0), 0.3, springTolerance());
  const double meanShift = (sim.positions().col(0) - rest.col(0)).mean();
  EXPECT_NEAR(meanShift, 0.3, 0.05);
}

TEST_P(Handle, HermiteHandleAndFixedPinTogether) {
  nlohmann::json doc = test::hangingClothScene(kSize, kQuads, 0.01, 0, 300.0, 1e-3, kDensity);
  doc["solver"]["method"] = GetParam();
  // Corner 0 stays pinned; corner kQuads swings on a Hermite curve towards the viewer and up.
  doc["cloths"][0]["attachments"] = {
      {{"vertices", {0}}, {"kind", "fixed"}, {"stiffness", kStiffness}},
      {{"vertices", {kQuads}},
       {"kind", "handle"},
       {"stiffness", kStiffness},
       {"trajectory",
        {{"hermite",
          {{"times", {0.0, 0.5, 1.0}},
           {"points", {{0, 0, 0}, {-0.05, 0.05, 0.15}, {-0.1, 0.1, 0.2}}},
           {"tangents", {{0, 0, 0}, {-0.1, 0.2, 0.3}, {0, 0, 0}}}}}}}}};
  const Scene scene = test::parse(doc);
  Simulator sim(scene);
  const HandleTrajectory& trajectory = scene.cloths[0].attachments[1].trajectory;
  const NodeMatrix rest = sim.positions();
  double worstHandle = 0.0, worstPin = 0.0;
  for (int n = 1; n <= 120; ++n) {
    sim.step();
    const Vec3 target = trajectory.target(rest.row(kQuads).transpose(), sim.time());
    worstHandle = std::max(worstHandle, (sim.positions().row(kQuads).transpose() - target).norm());
    worstPin = std::max(worstPin, (sim.positions().row(0) - rest.row(0)).norm());
  }
  EXPECT_LT(worstHandle, springTolerance());
  EXPECT_LT(worstPin, springTolerance());
  EXPECT_NEAR((sim.positions().row(kQuads) - rest.row(kQuads)).norm(), Vec3(-0.1, 0.1, 0.2).norm(),
              springTolerance());
}

INSTANTIATE_TEST_SUITE_P(Solvers, Handle, ::testing::Values("newton", "pd"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace weft
