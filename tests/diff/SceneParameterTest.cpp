// Parameters by JSON path: which paths resolve to which kind, which are rejected (naming the
// option or task entry), and the typed setters, which must agree with the strict loader.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/SceneParameter.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

TEST(ParameterSet, SetsValuesCheckedAsTheLoaderChecksThem) {
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

// A scene holding every kind of parameter: the handle scene (wind, a nodal force, an initial
// velocity, gravity, a Hermite handle with its stiffness) with a distant sphere and self-collision.
nlohmann::json everyKindScene() {
  nlohmann::json doc = test::handleScene(6);
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.0, -5.0, 0.0}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  doc["cloths"][0]["self_collision"] = {{"radius", 0.004}, {"friction", 0.2}};
  return doc;
}

// The value a test writes: away from the current one, inside every kind's range.
double changedValue(double current) {
  return current == 0.0 ? 0.125 : current * 0.75 + 0.01;
}

// The typed setter against the loader it replaces: for every parameter of the scene, the same
// document, the same value read back, and a bit-identical simulation.
TEST(ParameterSet, TypedSettersAgreeWithTheLoaderForEveryParameter) {
  const Scene scene = test::parse(everyKindScene());
  const std::vector<std::string> paths = differentiableParameterPaths(scene);
  std::vector<SceneParameter::Kind> kinds;
  const Trajectory base = runForwardPass(scene).trajectory;
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const ParameterSet set = ParameterSet::fromPaths(scene, {path});
    Eigen::VectorXd v = set.values(scene);
    v[0] = changedValue(v[0]);
    const Scene typed = set.withValues(scene, v);
    const Scene loaded = withDocumentValue(scene, path, v[0]);
    EXPECT_EQ(typed.document, loaded.document);
    EXPECT_EQ(parameterValue(typed, set[0]), v[0]);
    EXPECT_EQ(parameterValue(loaded, set[0]), v[0]);
    // Simulated once per kind (its first path: knot 0 of a handle, which acts from the start).
    if (std::find(kinds.begin(), kinds.end(), set[0].kind) != kinds.end()) continue;
    kinds.push_back(set[0].kind);
    const Trajectory a = runForwardPass(typed).trajectory;
    const Trajectory b = runForwardPass(loaded).trajectory;
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (std::size_t n = 0; n < a.positions.size(); ++n) {
      ASSERT_TRUE(a.positions[n] == b.positions[n]) << "state " << n;
    }
    // The change must reach the simulation for every kind but the far obstacle's friction and the
    // self-collision friction (no contact happens in six steps): else the check above proves
    // little.
    if (set[0].kind != SceneParameter::Kind::ObstacleFriction &&
        set[0].kind != SceneParameter::Kind::SelfCollisionFriction) {
      EXPECT_FALSE(a.positions.back() == base.positions.back());
    }
  }
  // Every kind is exercised.
  for (int k = 0; k <= static_cast<int>(SceneParameter::Kind::AttachmentStiffness); ++k)
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), static_cast<SceneParameter::Kind>(k)),
              kinds.end())
        << "kind " << k << " not among the scene's parameters";
}

// Out-of-range and non-finite values: the typed setter refuses exactly what the loader refuses,
// with the same message, and accepts what it accepts.
TEST(ParameterSet, TypedSettersRefuseWhatTheLoaderRefuses) {
  const Scene scene = test::parse(everyKindScene());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, double>> cases = {
      {"cloths.0.material.density", 0.0},
      {"cloths.0.material.density", -1.0},
      {"cloths.0.material.stretch", -1.0},
      {"cloths.0.material.stretch", 2e12},
      {"cloths.0.material.bend", -1e-3},
      {"cloths.0.attachments.1.stiffness", 0.0},
      {"cloths.0.attachments.1.stiffness", 2e12},
      {"obstacles.0.friction", -0.1},
      {"obstacles.0.friction", 1e4},
      {"cloths.0.self_collision.friction", -0.1},
      {"wind.strength", 2e6},
      {"wind.frequency", -1.0},
      {"wind.phase", -2e6},
      {"gravity.1", nan},
      {"cloths.0.initial_velocity.0", inf},
      {"cloths.0.forces.0.force.2", nan},
      {"cloths.0.attachments.1.trajectory.hermite.points.1.0", nan},
      {"cloths.0.attachments.1.trajectory.hermite.tangents.2.1", -inf},
      {"cloths.0.material.stretch", 0.0},  // accepted by both
  };
  int refused = 0;
  for (const auto& [path, value] : cases) {
    SCOPED_TRACE(path + " = " + std::to_string(value));
    const ParameterSet set = ParameterSet::fromPaths(scene, {path});
    std::string typedError = "accepted", loaderError = "accepted";
    try {
      set.withValues(scene, Eigen::VectorXd::Constant(1, value));
    } catch (const InputError& e) {
      typedError = e.what();
    }
    try {
      withDocumentValue(scene, path, value);
    } catch (const InputError& e) {
      loaderError = e.what();
    }
    EXPECT_EQ(typedError, loaderError);
    refused += typedError != "accepted";
  }
  EXPECT_EQ(refused, static_cast<int>(cases.size()) - 1);
}

// A wind direction set to zero one component at a time: refused once the vector is zero, naming
// the vector as the loader does.
TEST(ParameterSet, ZeroWindDirectionIsRefusedAsByTheLoader) {
  const Scene scene = test::parse(everyKindScene());
  const ParameterSet set =
      ParameterSet::fromPaths(scene, {"wind.direction.0", "wind.direction.1", "wind.direction.2"});
  try {
    set.withValues(scene, Eigen::Vector3d::Zero());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), "wind.direction");
    EXPECT_NE(std::string(e.what()).find("nonzero"), std::string::npos) << e.what();
  }
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
