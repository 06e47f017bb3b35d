// System identification (issue 4, DiffCloth Sec. 6): a small cloth hanging in wind, or a ribbon
// sliding down an incline, whose target motion is simulated with known parameters; starting
// elsewhere, L-BFGS-B over the adjoint gradient recovers them to within 1%.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/diff/ForwardPass.h>
#include <weft/optim/LbfgsbOptimizer.h>
#include <weft/optim/SimulationObjective.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

struct Recovery {
  OptimizationResult result;
  Eigen::VectorXd values;
};

// Optimises the task of `document` (target written from `targetDocument`) over `parameters`.
Recovery recover(const test::TempDir& dir, const nlohmann::json& document,
                 const nlohmann::json& targetDocument, const std::vector<std::string>& parameters) {
  nlohmann::json doc = document;
  test::addTask(doc, "trajectory",
                test::writeTargetTrajectory(targetDocument, dir.file("target.npy")), parameters);
  // The same tight forward solver as the target's: the loss then has an exact zero at the
  // generating parameters, and the adjoint gradient is that of the computed loss.
  const Scene scene = withTightForwardSolver(test::parse(doc), 1e-8);
  SimulationObjective objective(scene, ParameterSet::fromTask(scene));
  OptimizerSettings settings;
  settings.maxEvaluations = 60;
  LbfgsbOptimizer optimizer(settings);
  const ParameterSpace& space = objective.space();
  Recovery r;
  r.result = optimizer.minimize(objective, space.toCoordinates(space.initialValues()),
                                space.lowerCoordinates(), space.upperCoordinates());
  r.values = space.toValues(r.result.x);
  EXPECT_EQ(r.result.steps, 2LL * scene.time.steps * r.result.evaluations);
  return r;
}

TEST(SystemIdentification, RecoversStretchStiffness) {
  test::TempDir dir;
  const nlohmann::json doc = test::windClothScene(6, 25);  // stretch 300 N/m
  nlohmann::json target = doc;
  target["cloths"][0]["material"]["stretch"] = 250.0;
  const Recovery r = recover(dir, doc, target, {"cloths.0.material.stretch"});
  EXPECT_NEAR(r.values[0], 250.0, 2.5)
      << r.result.stopReason << ", " << r.result.evaluations << " evaluations";
  EXPECT_LT(r.result.loss, 1e-6);
}

TEST(SystemIdentification, RecoversStretchAndWindStrengthTogether) {
  test::TempDir dir;
  const nlohmann::json doc = test::windClothScene(6, 25);  // stretch 300, wind strength 1.5
  nlohmann::json target = doc;
  target["cloths"][0]["material"]["stretch"] = 250.0;
  target["wind"]["strength"] = 2.0;
  const Recovery r = recover(dir, doc, target, {"cloths.0.material.stretch", "wind.strength"});
  EXPECT_NEAR(r.values[0], 250.0, 2.5) << r.result.stopReason;
  EXPECT_NEAR(r.values[1], 2.0, 0.02) << r.result.stopReason;
}

TEST(SystemIdentification, RecoversDensity) {
  test::TempDir dir;
  const nlohmann::json doc = test::windClothScene(6, 25);
  nlohmann::json target = doc;
  const double start = doc["cloths"][0]["material"]["density"].get<double>();
  target["cloths"][0]["material"]["density"] = 1.3 * start;
  const Recovery r = recover(dir, doc, target, {"cloths.0.material.density"});
  EXPECT_NEAR(r.values[0], 1.3 * start, 0.013 * start) << r.result.stopReason;
}

TEST(SystemIdentification, RecoversObstacleFrictionThroughTheContactAdjoint) {
  // A ribbon sliding down a 20 degree plane (every node in the slip branch): its motion is set by
  // mu (acceleration g (sin 20 - mu cos 20)), whose gradient comes through ContactAdjoint.
  test::TempDir dir;
  const nlohmann::json doc = test::inclineScene();
  nlohmann::json target = doc;
  target["obstacles"][0]["friction"] = 0.25;
  const Recovery r = recover(dir, doc, target, {"obstacles.0.friction"});
  EXPECT_NEAR(r.values[0], 0.25, 0.0025)
      << r.result.stopReason << ", " << r.result.evaluations << " evaluations";
  EXPECT_LT(r.result.loss, 1e-8);
}

}  // namespace
}  // namespace weft
