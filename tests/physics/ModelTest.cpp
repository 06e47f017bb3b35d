// The compiled model (physics/Model.h): built once from a scene, immutable under use, holding
// only what the scene calls for, and shared by every simulator run from it and by the
// trajectories they record.

#include <support/SceneBuilder.h>
#include <weft/contact/ObstacleShape.h>
#include <weft/physics/ExternalForce.h>
#include <weft/physics/Model.h>
#include <weft/physics/ProjectiveConstraint.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace weft {
namespace {

// A cloth hanging from its top corners whose top middle vertex a handle drags sideways, in wind:
// every kind of per-step state a constraint or force holds (the handle's targets, the
// projections' derivatives).
nlohmann::json draggedClothScene() {
  nlohmann::json doc = test::hangingClothScene(0.4, 6, 0.01, 0, 300.0, 1e-3);
  doc["wind"] = {{"direction", {0.2, 0.0, 1.0}}, {"strength", 1.5}, {"frequency", 2.0}};
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {3}},
       {"kind", "handle"},
       {"stiffness", 500.0},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.3}, {"offset", {0, 0, 0.2}}}}}}}});
  doc["solver"] = {{"method", "newton"}, {"pd_iterations", 200}, {"pd_tolerance", 1e-6}};
  return doc;
}

std::vector<std::string> namesOf(const std::vector<std::unique_ptr<ProjectiveConstraint>>& v) {
  std::vector<std::string> names;
  for (const auto& c : v) names.emplace_back(c->name());
  return names;
}

TEST(Model, RunsFromOneModelAreBitIdenticalToRunsFromTheScene) {
  const Scene scene = test::parse(draggedClothScene());
  const std::shared_ptr<const Model> model = Model::compile(scene);
  // Two runs from the same model, one after the other and interleaved with a third: the
  // model's families must not carry state from one run into another.
  Simulator first(model), second(model), fromScene(scene);
  Trajectory a, b, c;
  first.run(15, a);
  second.run(5, b);
  fromScene.run(15, c);
  second.run(10, b);
  const std::vector<double> pa = a.flattenedPositions(), pb = b.flattenedPositions(),
                            pc = c.flattenedPositions();
  ASSERT_EQ(pa.size(), pb.size());
  ASSERT_EQ(pa.size(), pc.size());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(pa.data(), pc.data(), pa.size() * sizeof(double)), 0);
  // Not a static scene: the handle moved the cloth.
  EXPECT_GT((a.positions.back() - a.positions.front()).cwiseAbs().maxCoeff(), 0.05);
}

TEST(Model, TheTrajectoryRefersToTheModelItWasSimulatedWith) {
  const std::shared_ptr<const Model> model = Model::compile(test::parse(draggedClothScene()));
  Simulator sim(model);
  EXPECT_EQ(sim.sharedModel(), model);
  EXPECT_EQ(&sim.cloth(), &model->cloth());  // the nodal system is the model's, not a copy
  Trajectory t;
  sim.run(2, t);
  EXPECT_EQ(t.model, model);
  EXPECT_EQ(model->dt(), 0.01);
}

TEST(Model, HoldsOnlyWhatTheSceneNames) {
  // A flat hanging cloth: bending projects to zero but still shapes P, so it is a family; wind
  // is absent, and there is no contact.
  nlohmann::json doc = test::hangingClothScene(0.4, 6, 0.01, 10, 300.0, 1e-3);
  doc.erase("wind");
  const std::shared_ptr<const Model> plain = Model::compile(test::parse(doc));
  EXPECT_EQ(namesOf(plain->constraints()),
            (std::vector<std::string>{"stretch", "bending", "attachments"}));
  ASSERT_EQ(plain->forces().size(), 1u);
  EXPECT_STREQ(plain->forces()[0]->name(), "gravity");
  EXPECT_FALSE(plain->hasContact());
  EXPECT_TRUE(plain->obstacleShapes().empty());

  const std::shared_ptr<const Model> dragged = Model::compile(test::parse(draggedClothScene()));
  EXPECT_EQ(namesOf(dragged->constraints()),
            (std::vector<std::string>{"stretch", "bending", "attachments", "handles"}));
  ASSERT_EQ(dragged->forces().size(), 2u);
  EXPECT_STREQ(dragged->forces()[1]->name(), "wind");
  // A simulator's families are its own instances of the model's, with the same rows.
  Simulator sim(dragged);
  ASSERT_EQ(sim.constraints().size(), dragged->constraints().size());
  for (std::size_t k = 0; k < sim.constraints().size(); ++k) {
    EXPECT_NE(sim.constraints()[k].get(), dragged->constraints()[k].get());
    EXPECT_EQ(sim.constraints()[k]->weights(), dragged->constraints()[k]->weights());
  }
  EXPECT_EQ(sim.moduleNames(),
            (std::vector<std::string>{"solver", "stretch", "bending", "attachments", "handles",
                                      "gravity", "wind"}));
}

TEST(Model, ObstacleShapesAreBuiltOnceAndShared) {
  nlohmann::json doc = test::gridScene(0.4, 6, 0.01, 5);
  doc["obstacles"] = {{{"sphere", {{"center", {0.0, -0.3, 0.0}}, {"radius", 0.2}}}}};
  const std::shared_ptr<const Model> model = Model::compile(test::parse(doc));
  ASSERT_EQ(model->obstacleShapes().size(), 1u);
  EXPECT_TRUE(model->hasContact());
  const std::shared_ptr<const ObstacleShape>& shape = model->obstacleShapes()[0];
  EXPECT_STREQ(shape->name(), "sphere");
  EXPECT_EQ(shape.use_count(), 1);
  {
    Simulator a(model), b(model);  // each poses the same shape, none builds its own
    EXPECT_EQ(shape.use_count(), 3);
  }
  EXPECT_EQ(shape.use_count(), 1);
}

}  // namespace
}  // namespace weft
