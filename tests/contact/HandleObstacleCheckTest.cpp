// The scene check that warns when a handle's targets go inside an obstacle (the Sock's starting
// guess drove two cuff handles 18 mm into the foot: 200 N springs against the contact, steps
// unconverged from step 187). It names the attachment and the obstacle, the first time and the
// depth; a handle that passes beside the obstacle, or only through its skin, is not reported;
// a moving obstacle that comes onto a handle is.

#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/contact/HandleObstacleCheck.h>
#include <weft/contact/HandleTargetSamples.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

// A 0.2 m cloth at the origin whose corner 0 (at (-0.1, 0, -0.1)) is a handle moving by `end`
// over [0, 1] s; a sphere of radius 0.1 at (0.3, 0, -0.1), 100 steps of 0.01 s.
nlohmann::json scene(const Vec3& end) {
  nlohmann::json doc = test::clothScene(0.2, 4, Vec3::Zero(), 0.01);
  doc["time"]["steps"] = 100;
  doc["cloths"][0]["attachments"] = {
      {{"vertices", {0}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}},
           {{"time", 1.0}, {"offset", {end.x(), end.y(), end.z()}}}}}}}}};
  test::addObstacle(doc, "sphere", {{"center", {0.3, 0.0, -0.1}}, {"radius", 0.1}}, 0.3);
  return doc;
}

TEST(HandleObstacleCheck, NamesAHandleDrivenIntoAnObstacle) {
  // The corner moves 0.45 m along +X: it enters the sphere at x = 0.2 (t = 0.667 s, first
  // sampled inside at 0.67 s) and is deepest at t = 0.89 s, 0.5 mm past the centre (99.5 mm).
  const std::vector<std::string> messages =
      handlesEnteringObstacles(test::parse(scene(Vec3(0.45, 0, 0))));
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("cloths.0.attachments.0"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("obstacles.0 (sphere)"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("t = 0.67 s"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("99.5 mm deep"), std::string::npos) << messages[0];
}

TEST(HandleObstacleCheck, SaysNothingForAHandleThatStaysOutside) {
  // Along +Z the corner passes 0.3 m from the sphere's centre; along +X by 0.1995 m it stops
  // inside the skin (1 mm) but outside the surface.
  EXPECT_TRUE(handlesEnteringObstacles(test::parse(scene(Vec3(0, 0, 0.5)))).empty());
  EXPECT_TRUE(handlesEnteringObstacles(test::parse(scene(Vec3(0.1995, 0, 0)))).empty());
}

TEST(HandleObstacleCheck, SeesAMovingObstacleComeOntoAHandle) {
  nlohmann::json doc = scene(Vec3::Zero());  // the handle stays put
  // Its near side, at x = 0.2 - 0.45 t, reaches the corner (x = -0.1) at t = 0.667 s.
  doc["obstacles"][0]["motion"] = {
      {"keyframes",
       {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 1.0}, {"offset", {-0.45, 0, 0}}}}}};
  const std::vector<std::string> messages = handlesEnteringObstacles(test::parse(doc));
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("t = 0.67 s"), std::string::npos) << messages[0];
}

TEST(HandleObstacleCheck, SamplesOnlyScenesWithAHandleAndAnObstacle) {
  const nlohmann::json doc = scene(Vec3(0.45, 0, 0));
  EXPECT_TRUE(hasHandlesAndObstacles(test::parse(doc)));
  nlohmann::json noObstacle = doc;
  noObstacle.erase("obstacles");
  EXPECT_FALSE(hasHandlesAndObstacles(test::parse(noObstacle)));
  nlohmann::json pinned = doc;  // the same vertex held fixed is not a handle
  pinned["cloths"][0]["attachments"][0]["kind"] = "fixed";
  pinned["cloths"][0]["attachments"][0].erase("trajectory");
  EXPECT_FALSE(hasHandlesAndObstacles(test::parse(pinned)));
  EXPECT_TRUE(handlesEnteringObstacles(test::parse(pinned)).empty());
}

}  // namespace
}  // namespace weft
