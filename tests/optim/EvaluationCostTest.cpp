// What an evaluation of a simulation costs, as DiffCloth's tables count it: a forward step 1, a
// backward step 1 more. On a tiny scene (a 4 x 4 cloth in wind, 10 steps): a gradient evaluation
// costs 2 * 10 steps, a value-only one 10; the value alone equals the loss a gradient evaluation
// reports; every method stays within its budget and logs the kind of evaluation it made; an
// evaluation reads no file (the scene is loaded once, its parameters set in memory).

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/io/ObjWriter.h>
#include <weft/optim/Optimizer.h>
#include <weft/optim/SimulationObjective.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace weft {
namespace {

constexpr int kSteps = 10;

Scene tinyTaskScene(const test::TempDir& dir) {
  return test::withTrajectoryTask(dir, test::windClothScene(4, kSteps),
                                  {"cloths.0.material.stretch", "wind.strength"});
}

TEST(EvaluationCost, ValueCostsTheForwardStepsAndMatchesTheGradientEvaluation) {
  test::TempDir dir;
  const Scene scene = tinyTaskScene(dir);
  SimulationObjective objective(scene, ParameterSet::fromTask(scene));
  EXPECT_EQ(objective.stepsPerEvaluation(), 2 * kSteps);
  EXPECT_EQ(objective.stepsPerValue(), kSteps);
  const Eigen::VectorXd z = objective.space().toCoordinates(objective.space().initialValues());
  Eigen::VectorXd gradient;
  const double withGradient = objective.evaluate(z, gradient);
  EXPECT_EQ(gradient.size(), 2);
  EXPECT_GT(withGradient, 0.0);
  EXPECT_EQ(objective.value(z), withGradient);
}

// The cloth and an obstacle come from mesh files and the loss from a target file; once the
// objective exists, deleting all of them changes no evaluation, with or without a gradient.
TEST(EvaluationCost, AnEvaluationReadsNoFile) {
  test::TempDir dir;
  nlohmann::json doc = test::windClothScene(4, kSteps);
  const Scene grid = test::parse(doc);
  test::addTask(doc, "trajectory", test::writeTargetTrajectory(doc, dir.file("target.npy")),
                {"cloths.0.material.stretch", "wind.strength"});
  writeObj(dir.file("cloth.obj"), grid.cloths[0].mesh);
  writeObj(dir.file("rock.obj"), grid.cloths[0].mesh);  // a sheet 0.5 m below the cloth
  doc["cloths"][0]["mesh"] = {{"file", "cloth.obj"}};
  doc["obstacles"] = {
      {{"mesh", {{"file", "rock.obj"}, {"transform", {{"translate", {0, -0.5, 0}}}}}},
       {"friction", 0.3}}};
  std::ofstream(dir.file("scene.json")) << doc.dump(2);
  const Scene scene = loadScene(dir.file("scene.json"));
  SimulationObjective objective(scene, ParameterSet::fromTask(scene));
  Eigen::VectorXd z = objective.space().toCoordinates(objective.space().initialValues());
  z[0] += 0.1;  // away from the target's values, so the gradient is not zero
  Eigen::VectorXd before, after;
  const double lossBefore = objective.evaluate(z, before);
  const double valueBefore = objective.value(z);
  for (const char* name : {"cloth.obj", "rock.obj", "target.npy", "scene.json"})
    ASSERT_TRUE(std::filesystem::remove(dir.file(name))) << name;
  EXPECT_EQ(objective.evaluate(z, after), lossBefore);
  EXPECT_EQ(objective.value(z), valueBefore);
  EXPECT_TRUE(after == before);
  EXPECT_GT(before.norm(), 0.0);
}

TEST(EvaluationCost, BudgetCountsGradientEvaluationsTwiceAndValuesOnce) {
  test::TempDir dir;
  const Scene scene = tinyTaskScene(dir);
  const long long budget = 7 * kSteps + 5;  // 3 gradient evaluations or 7 value-only ones
  for (const std::string method : {"lbfgsb", "adam", "cmaes", "es1p1"}) {
    SCOPED_TRACE(method);
    SimulationObjective objective(scene, ParameterSet::fromTask(scene));
    OptimizerSettings settings;
    settings.budget = budget;
    settings.gradientTolerance = 0.0;
    settings.lossTolerance = 0.0;
    std::unique_ptr<Optimizer> optimizer = makeOptimizer(method, settings);
    const ParameterSpace& space = objective.space();
    const OptimizationResult r =
        optimizer->minimize(objective, space.toCoordinates(space.initialValues()),
                            space.lowerCoordinates(), space.upperCoordinates());
    const bool gradients = optimizer->usesGradient();
    const long long cost = gradients ? 2 * kSteps : kSteps;
    EXPECT_EQ(r.stopReason, "budget");
    EXPECT_EQ(r.evaluations, gradients ? 3 : 7);
    EXPECT_EQ(r.steps, cost * r.evaluations);
    EXPECT_LE(r.steps, budget);
    long long previous = 0;
    for (const LogEntry& e : optimizer->log().entries()) {
      EXPECT_EQ(e.steps - previous, cost) << "evaluation " << e.evaluation;
      EXPECT_LE(e.steps, budget);
      EXPECT_EQ(e.hasGradient, gradients);
      previous = e.steps;
    }
  }
}

}  // namespace
}  // namespace weft
