// `--set` on keys the scene file leaves out together with their objects: a path the scene format
// defines creates the objects along it (solver.contact on a scene without "solver", wind on a
// scene without wind), a path the format does not define stays a bad-input error (exit 2)
// naming the option, and nothing is written then.

#include "CliSupport.h"

#include <support/SceneBuilder.h>

#include <nlohmann/json.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::describe;
using test::expectBadInput;
using test::readFile;
using test::runWeft;
using test::TempDir;

// The hanging cloth (in the XY plane, two top corners pinned) without "solver" and "wind".
std::string bareScene(const TempDir& dir) {
  nlohmann::json doc = test::hangingClothScene(0.4, 4, 0.01, 10, 300.0, 0.001);
  doc.erase("solver");
  doc.erase("wind");
  return test::writeScene(dir.file("bare.json"), doc);
}

nlohmann::json simulatedScene(const std::string& outDir) {
  return nlohmann::json::parse(readFile(outDir + "/scene.json"));
}

// Mean z of the last state's vertices (the cloth hangs in z = 0 without wind).
double finalMeanZ(const std::string& outDir) {
  const test::ParsedNpy npy = test::parseNpy(readFile(outDir + "/positions.npy"));
  if (npy.shape.size() != 3 || npy.data.empty()) return 0.0;
  const std::size_t vertices = npy.shape[1], last = npy.shape[0] - 1;
  double sum = 0.0;
  for (std::size_t i = 0; i < vertices; ++i) sum += npy.data[(last * vertices + i) * 3 + 2];
  return sum / vertices;
}

TEST(SetAbsentObject, ASolverKeyCreatesTheSolverObject) {
  TempDir dir;
  const std::string scene = bareScene(dir);
  const test::ProcessResult r = runWeft({"simulate", scene, "--set", "solver.contact=\"newton\"",
                                         "--out", dir.file("run"), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_EQ(simulatedScene(dir.file("run"))["solver"], (nlohmann::json{{"contact", "newton"}}));
}

TEST(SetAbsentObject, NestedAbsentObjectsAreAllCreated) {
  TempDir dir;
  const std::string scene = bareScene(dir);
  const test::ProcessResult r = runWeft(
      {"simulate", scene, "--set", "solver.backward.tolerance=1e-8", "--set",
       "solver.backward.method=direct", "--out", dir.file("run"), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_EQ(simulatedScene(dir.file("run"))["solver"],
            (nlohmann::json{{"backward", {{"tolerance", 1e-8}, {"method", "direct"}}}}));
}

TEST(SetAbsentObject, ACreatedWindBlowsTheCloth) {
  // Wind along +z on a cloth hanging in the XY plane: without it the cloth stays in z = 0 (by
  // symmetry), with it the cloth is pushed towards +z.
  TempDir dir;
  const std::string scene = bareScene(dir);
  const test::ProcessResult calm =
      runWeft({"simulate", scene, "--out", dir.file("calm"), "--quiet", "--threads", "1"});
  ASSERT_EQ(calm.exitCode, 0) << describe(calm);
  const test::ProcessResult windy =
      runWeft({"simulate", scene, "--set", "wind.direction=[0,0,1]", "--set", "wind.strength=5",
               "--out", dir.file("windy"), "--quiet", "--threads", "1"});
  ASSERT_EQ(windy.exitCode, 0) << describe(windy);
  EXPECT_NEAR(finalMeanZ(dir.file("calm")), 0.0, 1e-9);
  EXPECT_GT(finalMeanZ(dir.file("windy")), 1e-3);
}

TEST(SetAbsentObject, UndefinedKeysUnderAbsentObjectsAreErrors) {
  TempDir dir;
  const std::string scene = bareScene(dir);
  const std::string out = dir.file("run");
  struct Case {
    std::string set, where, phrase;
  };
  const Case cases[] = {
      // An undefined key in an object the format defines (absent from the file).
      {"solver.nosuch=1", "--set solver.nosuch", "unknown path: solver.nosuch: unknown key"},
      // Nested under it, and under an object the format does not define.
      {"solver.backward.nosuch=1", "--set solver.backward.nosuch",
       "unknown path: solver.backward.nosuch: unknown key"},
      {"solver.nosuch.deeper=1", "--set solver.nosuch.deeper",
       "unknown path: solver.nosuch: unknown key"},
      {"nosuch.key=1", "--set nosuch.key", "unknown path: nosuch: unknown key"},
      // A misspelt object in an existing one.
      {"cloths.0.materia.stretch=5", "--set cloths.0.materia.stretch",
       "unknown path: cloths.0.materia: unknown key"},
      // Arrays are never created: the scene has no obstacles.
      {"obstacles.0.friction=0.2", "--set obstacles.0.friction", "unknown path"},
      // A created object must still be complete: wind needs its direction.
      {"wind.strength=5", "--set wind.strength", "missing required key 'direction'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.set);
    const test::ProcessResult r =
        expectBadInput("simulate", {scene, "--set", c.set, "--out", out}, c.where, c.phrase);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace weft
