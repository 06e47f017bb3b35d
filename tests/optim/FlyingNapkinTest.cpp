// The Flying Napkin scenes (DiffCloth Sec. 5.2, Fig. 4; assets/scenes/napkin_KxK.json, written by
// scripts/make-napkins.py): k x k nodes, one constant force per node as the task's 3 k^2
// parameters, each bounded, and a final-frame loss on the centre. Their adjoint gradient agrees
// with finite differences, and L-BFGS-B brings the centre onto its target.

#include <weft/diff/GradientCheck.h>
#include <weft/diff/ParameterSet.h>
#include <weft/optim/LbfgsbOptimizer.h>
#include <weft/optim/SimulationObjective.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

std::string napkin(int k) {
  return std::string(WEFT_ASSET_DIR) + "/scenes/napkin_" + std::to_string(k) + "x" +
         std::to_string(k) + ".json";
}

TEST(FlyingNapkin, ScenesHaveOneBoundedForcePerNodeAndACentreLoss) {
  for (int k : {4, 5, 7, 10}) {
    SCOPED_TRACE(k);
    const Scene scene = loadScene(napkin(k), {});
    EXPECT_EQ(scene.vertexCount(), k * k);
    ASSERT_TRUE(scene.task);
    const ParameterSet parameters = ParameterSet::fromTask(scene);
    ASSERT_EQ(parameters.size(), 3 * k * k);  // 48, 75, 147, 300 as in the paper
    const SimulationObjective objective(scene, parameters);
    for (const SceneParameter& p : objective.space().parameters()) {
      EXPECT_EQ(p.kind, SceneParameter::Kind::NodalForce) << p.path;
      EXPECT_TRUE(std::isfinite(p.lower) && std::isfinite(p.upper) && p.lower < 0.0 &&
                  p.upper > 0.0)
          << p.path;
    }
    const nlohmann::json& loss = scene.task->loss;
    ASSERT_TRUE(loss.contains("final"));
    EXPECT_EQ(loss["final"]["vertices"].size(),
              k % 2 == 1 ? 1u : 4u);  // the centre node or the central four
  }
}

TEST(FlyingNapkin, AdjointGradientMatchesFiniteDifferences) {
  // Away from the flat start (where out-of-plane forces act through a second-order membrane
  // response and finite differences need a tiny step): a few nodes pushed, then three forces
  // checked, one of them out of plane.
  Scene scene = loadScene(napkin(5), {});
  for (const auto& [path, value] :
       std::vector<std::pair<std::string, double>>{{"cloths.0.forces.6.force.1", 0.05},
                                                   {"cloths.0.forces.12.force.0", -0.03},
                                                   {"cloths.0.forces.20.force.2", 0.04}})
    scene = withDocumentValue(scene, path, value);
  const ParameterSet checked = ParameterSet::fromPaths(
      scene,
      {"cloths.0.forces.12.force.1", "cloths.0.forces.6.force.0", "cloths.0.forces.18.force.2"});
  const GradientCheckReport report = checkGradient(scene, checked, GradientCheckOptions{});
  ASSERT_EQ(report.entries.size(), 3u);
  for (const GradientCheckEntry& e : report.entries) {
    EXPECT_LT(e.relativeError, 1e-4)
        << e.param << ": adjoint " << e.adjoint << ", fd " << e.finiteDifference;
    EXPECT_GT(std::abs(e.adjoint), 1e-3) << e.param;
  }
}

TEST(FlyingNapkin, LbfgsbBringsTheCentreOntoItsTarget) {
  const Scene scene = loadScene(napkin(5), {});
  SimulationObjective objective(scene, ParameterSet::fromTask(scene));
  OptimizerSettings settings;
  settings.maxEvaluations = 12;
  LbfgsbOptimizer optimizer(settings);
  const ParameterSpace& space = objective.space();
  const OptimizationResult r =
      optimizer.minimize(objective, space.toCoordinates(space.initialValues()),
                         space.lowerCoordinates(), space.upperCoordinates());
  const double initial = optimizer.log().entries().front().loss;
  EXPECT_GT(initial, 1.0);  // zero forces: the napkin falls 1.2 m instead of rising 0.25 m
  EXPECT_LT(r.loss, 1e-4 * initial) << r.stopReason << ", " << r.evaluations << " evaluations";
  const Eigen::VectorXd values = space.toValues(r.x);
  for (int i = 0; i < values.size(); ++i) {
    EXPECT_GE(values[i], space.parameters()[i].lower);
    EXPECT_LE(values[i], space.parameters()[i].upper);
  }
}

}  // namespace
}  // namespace weft
