// Only the effects a scene names are built (spec: "simulate only the effects a scene calls
// for"): without obstacles and self-collision there is no contact module and no time is spent on
// contact; with them, exactly the named contact modules exist and their time is accounted.

#include "ContactTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace weft {
namespace {

bool has(const Simulator& sim, const std::string& name) {
  const auto& names = sim.moduleNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

double seconds(const Simulator& sim, const std::string& name) {
  const auto& names = sim.moduleNames();
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1.0 : sim.moduleSeconds()[it - names.begin()];
}

nlohmann::json baseScene() {
  return test::clothScene(0.3, 6, Vec3(0, 0.05, 0), 0.01);
}

TEST(ContactModules, NoObstaclesNoSelfCollisionBuildsNoContact) {
  const test::ContactRun run = test::runScene(baseScene(), 5);
  const Simulator& sim = *run.sim;
  EXPECT_EQ(sim.contact(), nullptr);
  for (const std::string& name : sim.moduleNames())
    EXPECT_EQ(name.find("contact"), std::string::npos) << name;
  EXPECT_FALSE(has(sim, "self_collision"));
  EXPECT_TRUE(run.trajectory.contacts.empty());
  EXPECT_TRUE(sim.lastContacts().points.empty());
  EXPECT_EQ(sim.moduleNames().size(), sim.moduleSeconds().size());
  for (const StepStats& s : run.trajectory.steps) {
    EXPECT_EQ(s.takeoff + s.stick + s.slip, 0);
    EXPECT_EQ(s.contactSweeps, 0);
    EXPECT_EQ(s.moduleSeconds.size(), sim.moduleNames().size());
  }
}

TEST(ContactModules, ObstaclesOnlyBuildDetectionAndSolve) {
  nlohmann::json doc = baseScene();
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.3);
  const test::ContactRun run = test::runScene(doc, 10);
  const Simulator& sim = *run.sim;
  ASSERT_NE(sim.contact(), nullptr);
  EXPECT_TRUE(has(sim, "contact_detection"));
  EXPECT_TRUE(has(sim, "contact_solve"));
  EXPECT_FALSE(has(sim, "self_collision"));
  EXPECT_GT(seconds(sim, "contact_detection"), 0.0);
  EXPECT_GT(seconds(sim, "contact_solve"), 0.0);
  EXPECT_EQ(run.trajectory.contacts.size(), 10u);
  EXPECT_GT(run.trajectory.steps.back().stick + run.trajectory.steps.back().slip, 0);
}

TEST(ContactModules, SelfCollisionOnlyBuildsSelfCollisionAndSolve) {
  nlohmann::json doc = baseScene();
  doc["cloths"][0]["self_collision"] = {{"radius", 0.01}, {"friction", 0.2}};
  const test::ContactRun run = test::runScene(doc, 5);
  const Simulator& sim = *run.sim;
  ASSERT_NE(sim.contact(), nullptr);
  EXPECT_FALSE(has(sim, "contact_detection"));
  EXPECT_TRUE(has(sim, "self_collision"));
  EXPECT_TRUE(has(sim, "contact_solve"));
  EXPECT_GT(seconds(sim, "self_collision"), 0.0);
}

TEST(ContactModules, ObstaclesAndSelfCollisionBuildAllThree) {
  nlohmann::json doc = baseScene();
  doc["cloths"][0]["self_collision"] = {{"radius", 0.01}, {"friction", 0.2}};
  test::addObstacle(doc, "sphere", {{"center", {0, -1, 0}}, {"radius", 0.5}}, 0.3);
  const test::ContactRun run = test::runScene(doc, 3);
  const Simulator& sim = *run.sim;
  for (const char* name : {"contact_detection", "self_collision", "contact_solve"}) {
    EXPECT_TRUE(has(sim, name)) << name;
    EXPECT_GE(seconds(sim, name), 0.0) << name;
  }
  EXPECT_EQ(std::count(sim.moduleNames().begin(), sim.moduleNames().end(), "contact_solve"), 1);
}

}  // namespace
}  // namespace weft
