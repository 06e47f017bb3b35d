// Parameters by JSON path: which paths resolve to which kind, which are rejected (naming the
// option or task entry), and setting values through the strict loader.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/SceneParameter.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

using Kind = SceneParameter::Kind;

TEST(SceneParameter, ResolvesEverySupportedPath) {
  const Scene scene = test::parse(test::windClothScene(4, 5));
  struct Case {
    const char* path;
    Kind kind;
    int cloth, index, component;
  };
  const Case cases[] = {{"cloths.0.material.stretch", Kind::Stretch, 0, -1, -1},
                        {"cloths.0.material.bend", Kind::Bend, 0, -1, -1},
                        {"cloths.0.material.density", Kind::Density, 0, -1, -1},
                        {"cloths.0.initial_velocity.2", Kind::InitialVelocity, 0, -1, 2},
                        {"cloths.0.forces.0.force.1", Kind::NodalForce, 0, 0, 1},
                        {"wind.strength", Kind::WindStrength, -1, -1, -1},
                        {"wind.direction.0", Kind::WindDirection, -1, -1, 0},
                        {"wind.frequency", Kind::WindFrequency, -1, -1, -1},
                        {"wind.phase", Kind::WindPhase, -1, -1, -1},
                        {"gravity.1", Kind::Gravity, -1, -1, 1}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    const SceneParameter p = resolveSceneParameter(scene, c.path, "--param");
    EXPECT_EQ(p.kind, c.kind);
    EXPECT_EQ(p.cloth, c.cloth);
    EXPECT_EQ(p.index, c.index);
    EXPECT_EQ(p.component, c.component);
    EXPECT_FALSE(p.logScale);
  }
  EXPECT_DOUBLE_EQ(parameterValue(scene, resolveSceneParameter(scene, "wind.phase", "x")), 0.3);
}

// The list the editor offers: exactly the paths that resolve, found by walking the document.
TEST(SceneParameter, ListsEveryDifferentiablePathOfTheScene) {
  nlohmann::json doc = test::windClothScene(4, 5);
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.0, -1.0, 0.0}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  const test::TempDir dir;
  // The task is not a source of parameters (its bounds and weights are numbers too).
  test::addTask(doc, "trajectory", test::writeTargetTrajectory(doc, dir.file("target.npy")),
                {"wind.strength"});
  doc["task"]["bounds"] = {{"wind.strength", {0.5, 3.0}}};
  const Scene scene = test::parse(doc);
  const std::vector<std::string> paths = differentiableParameterPaths(scene);
  const std::vector<std::string> expected = {"cloths.0.forces.0.force.0",
                                             "cloths.0.forces.0.force.1",
                                             "cloths.0.forces.0.force.2",
                                             "cloths.0.initial_velocity.0",
                                             "cloths.0.initial_velocity.1",
                                             "cloths.0.initial_velocity.2",
                                             "cloths.0.material.bend",
                                             "cloths.0.material.density",
                                             "cloths.0.material.stretch",
                                             "gravity.0",
                                             "gravity.1",
                                             "gravity.2",
                                             "obstacles.0.friction",
                                             "wind.direction.0",
                                             "wind.direction.1",
                                             "wind.direction.2",
                                             "wind.frequency",
                                             "wind.phase",
                                             "wind.strength"};
  EXPECT_EQ(paths, expected);
  for (const std::string& p : paths) EXPECT_NO_THROW(resolveSceneParameter(scene, p, "x")) << p;
}

TEST(SceneParameter, RejectsUnknownAndNonDifferentiablePaths) {
  const Scene scene = test::parse(test::windClothScene(4, 5));
  for (const char* path :
       {"cloths.3.material.stretch", "cloths.0.material.stiffness", "time.dt",
        "cloths.0.attachments.0.stiffness", "wind.direction", "wind.direction.5"}) {
    SCOPED_TRACE(path);
    try {
      resolveSceneParameter(scene, path, std::string("--param ") + path);
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), std::string("--param ") + path);
      EXPECT_EQ(e.file(), "test-scene.json");
    }
  }
}

TEST(ParameterSet, SetsValuesThroughTheLoader) {
  const Scene scene = test::parse(test::windClothScene(4, 5));
  const ParameterSet set =
      ParameterSet::fromPaths(scene, {"cloths.0.material.density", "wind.direction.2"});
  Eigen::VectorXd v = set.values(scene);
  EXPECT_DOUBLE_EQ(v[0], 0.1);
  EXPECT_DOUBLE_EQ(v[1], 1.0);
  v << 0.25, 3.0;
  const Scene changed = set.withValues(scene, v);
  EXPECT_DOUBLE_EQ(changed.cloths[0].material.density, 0.25);
  EXPECT_DOUBLE_EQ(changed.wind->direction.z(), 3.0);
  v[0] = -1.0;  // the loader's own range check applies
  EXPECT_THROW(set.withValues(scene, v), InputError);
}

TEST(ParameterSet, TaskEntriesAreNamedByTheirJsonPath) {
  nlohmann::json doc = test::windClothScene(4, 5);
  test::addTask(doc, "final", "x.npy", {"wind.strength", "time.dt"});
  const Scene scene = test::parse(doc);
  try {
    ParameterSet::fromTask(scene);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), "task.parameters.1");
  }
}

}  // namespace
}  // namespace weft
