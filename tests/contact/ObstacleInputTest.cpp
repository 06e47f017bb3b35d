// Malformed obstacle entries are input errors naming the file, the JSON path and the problem
// (spec: `error: <file>: <json path>: <what>`, exit 2): checked on the loader for each case,
// and through the real binary for the exit code and the message format.

#include "ContactTestSupport.h"

#include <app/CliSupport.h>
#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/scene/SceneLoader.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

namespace weft {
namespace {

struct BadObstacle {
  const char* name;
  const char* entry;  // the obstacle's JSON
  const char* path;
  const char* phrase;
};

void PrintTo(const BadObstacle& c, std::ostream* os) {
  *os << c.name;
}

const BadObstacle kCases[] = {
    {"NegativeSphereRadius", R"({"sphere": {"center": [0,0,0], "radius": -0.4}})",
     "obstacles.0.sphere.radius", "must be > 0, got -0.4"},
    {"ZeroCapsuleRadius", R"({"capsule": {"a": [0,0,0], "b": [1,0,0], "radius": 0}})",
     "obstacles.0.capsule.radius", "must be > 0"},
    {"ZeroPlaneNormal", R"({"plane": {"point": [0,0,0], "normal": [0,0,0]}})",
     "obstacles.0.plane.normal", "must be a nonzero vector"},
    {"UnknownObstacleKey", R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "frition": 0.3})",
     "obstacles.0.frition", "unknown key"},
    {"UnknownShapeKey", R"({"sphere": {"centre": [0,0,0], "radius": 0.4}})",
     "obstacles.0.sphere.centre", "unknown key"},
    {"NoShape", R"({"friction": 0.3})", "obstacles.0", "needs exactly one of: plane, sphere"},
    {"TwoShapes",
     R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "plane": {"point": [0,0,0], "normal": [0,1,0]}})",
     "obstacles.0", "give exactly one"},
    {"NegativeFriction", R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "friction": -1})",
     "obstacles.0.friction", "-1"},
    {"DegenerateCylinder", R"({"cylinder": {"a": [0,1,0], "b": [0,1,0], "radius": 0.1}})",
     "obstacles.0.cylinder.b", "must differ from 'a'"},
    {"NegativeBoxSize", R"({"box": {"center": [0,0,0], "size": [1,-1,1]}})",
     "obstacles.0.box.size.1", "must be > 0"},
    {"EmptyMotion", R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "motion": {}})",
     "obstacles.0.motion", "needs 'keyframes', 'hermite' or 'rotate'"},
    {"MotionTimesNotIncreasing",
     R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "motion": {"keyframes": [{"time": 1, "offset": [0,0,0]}, {"time": 0.5, "offset": [1,0,0]}]}})",
     "obstacles.0.motion.keyframes", "times must be strictly increasing"},
    {"MotionUnknownKey",
     R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "motion": {"keyframe": [{"time": 0, "offset": [0,0,0]}]}})",
     "obstacles.0.motion.keyframe", "unknown key"},
    {"MotionZeroRotationAxis",
     R"({"sphere": {"center": [0,0,0], "radius": 0.4}, "motion": {"rotate": {"center": [0,0,0], "axis": [0,0,0], "degrees_per_second": 90}}})",
     "obstacles.0.motion.rotate.axis", "must be a nonzero vector"},
};

nlohmann::json sceneWith(const char* entry) {
  nlohmann::json doc = test::clothScene(0.3, 4, Vec3(0, 1, 0), 0.01);
  doc["obstacles"] = nlohmann::json::array({nlohmann::json::parse(entry)});
  return doc;
}

class BadObstacleEntry : public ::testing::TestWithParam<BadObstacle> {};

TEST_P(BadObstacleEntry, LoaderNamesFilePathAndProblem) {
  const BadObstacle& c = GetParam();
  try {
    test::parse(sceneWith(c.entry), "bad-obstacle.json");
    FAIL() << "accepted " << c.entry;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad-obstacle.json");
    EXPECT_EQ(e.path(), c.path) << e.what();
    EXPECT_THAT(e.reason(), ::testing::HasSubstr(c.phrase)) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, BadObstacleEntry, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<BadObstacle>& info) {
                           return std::string(info.param.name);
                         });

TEST(BadObstacleCli, ExitsTwoWithTheMessageAndWritesNothing) {
  test::TempDir dir;
  for (const BadObstacle* c : {&kCases[0], &kCases[2], &kCases[3], &kCases[10]}) {
    const std::string scene =
        test::writeScene(dir.file(std::string(c->name) + ".json"), sceneWith(c->entry));
    const std::string out = dir.file("out");
    const test::ProcessResult r = test::runWeft({"simulate", scene, "--out", out});
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_THAT(r.err, ::testing::StartsWith("error: " + scene + ": " + c->path + ": "))
        << test::describe(r);
    EXPECT_THAT(r.err, ::testing::HasSubstr(c->phrase)) << test::describe(r);
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace weft
