// self_collision.model "impact_zones" (Liang et al. 2019) through the real binary: two cloths
// landing on each other stay free of edge-triangle crossings at every state, by the independent
// static check, with every step's impacts resolved; the module report names impact_zones and not
// the node model's self_collision; stats.csv carries the response's columns; the node model on
// the same scene is counted by the same check; a strip twisted through 720 degrees coils onto
// itself without a crossing, where the node model lets it pass through itself; a cloth folded
// onto itself and pressed stays free of crossings; gradients through impact zones are refused.

#include "CliSupport.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace weft {
namespace {

namespace t = weft::test;

const std::string kScene = std::string(WEFT_TEST_DATA_DIR) + "/scenes/two_cloths.json";
const std::string kTwistedStrip = std::string(WEFT_TEST_DATA_DIR) + "/scenes/twisted_strip.json";
const std::string kFoldedCloth = std::string(WEFT_TEST_DATA_DIR) + "/scenes/folded_cloth.json";

nlohmann::json summaryOf(const std::string& out) {
  return nlohmann::json::parse(t::readFile(out + "/summary.json"));
}

// The scene with each cloth's self_collision replaced, written next to the output.
std::string withSelfCollision(t::TempDir& dir, const nlohmann::json& selfCollision,
                              const nlohmann::json& task = nullptr,
                              const std::string& from = kScene) {
  nlohmann::json scene = nlohmann::json::parse(t::readFile(from));
  for (auto& cloth : scene["cloths"]) cloth["self_collision"] = selfCollision;
  if (!task.is_null()) scene["task"] = task;
  const std::string path = dir.file("scene.json");
  std::ofstream(path) << scene.dump(2);
  return path;
}

// weft simulate SCENE (one thread) into dir's "run"; its summary.json in `summary`.
void simulate(t::TempDir& dir, const std::string& scene, nlohmann::json& summary) {
  const std::string out = dir.file("run");
  const auto r = t::runWeft({"simulate", scene, "--out", out, "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << t::describe(r);
  summary = summaryOf(out);
}

// The impact-zone response acted (more than minZones zones), left no step unresolved, and no
// state has an edge through a face by the independent check.
void expectActedWithoutCrossing(const nlohmann::json& s, int minZones) {
  EXPECT_GT(s["impact_zones"]["zones_total"].get<int>(), minZones);
  EXPECT_EQ(s["impact_zones"]["unresolved_steps"], 0);
  EXPECT_EQ(s["crossings"]["max"], 0) << "at state " << s["crossings"]["max_state"];
  EXPECT_EQ(s["crossings"]["states_with_crossings"], 0);
}

TEST(ImpactZonesCli, TwoClothsLandingOnEachOtherNeverCross) {
  t::TempDir dir;
  const std::string out = dir.file("run");
  const auto r =
      t::runWeft({"simulate", kScene, "--out", out, "--quiet", "--strict", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << t::describe(r);
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  const nlohmann::json s = summaryOf(out);
  expectActedWithoutCrossing(s, 0);  // the upper cloth lands on the lower one
  // Nothing was moved far: the response corrects thickness-sized overlaps.
  EXPECT_LT(s["impact_zones"]["max_move"].get<double>(), 0.01);
  // Two cloths landing flat need no failsafe: every zone's QP answer is kept.
  EXPECT_EQ(s["impact_zones"]["rigid_zones_total"], 0);
  EXPECT_TRUE(s["modules"].contains("impact_zones"));
  EXPECT_FALSE(s["modules"].contains("self_collision"));
  const auto rows = t::readCsv(out + "/stats.csv");
  ASSERT_EQ(rows.size(), 61u);
  for (const char* column : {"impact_rounds", "impact_zones", "impact_constraints",
                             "impact_qp_iterations", "impact_rigid_zones", "impacts_resolved",
                             "impact_move", "crossings", "seconds_impact_zones"})
    EXPECT_NE(std::find(rows[0].begin(), rows[0].end(), column), rows[0].end()) << column;
  const auto resolved = static_cast<std::size_t>(
      std::find(rows[0].begin(), rows[0].end(), "impacts_resolved") - rows[0].begin());
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_EQ(rows[k][resolved], "1") << "step " << k;
}

TEST(ImpactZonesCli, TheNodeModelIsCountedByTheSameCheck) {
  t::TempDir dir;
  const std::string scene = withSelfCollision(dir, {{"radius", 0.004}, {"friction", 0.3}});
  const std::string out = dir.file("run");
  const auto r = t::runWeft({"simulate", scene, "--out", out, "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << t::describe(r);
  const nlohmann::json s = summaryOf(out);
  EXPECT_FALSE(s.contains("impact_zones"));
  EXPECT_TRUE(s["modules"].contains("self_collision"));
  EXPECT_FALSE(s["modules"].contains("impact_zones"));
  ASSERT_TRUE(s.contains("crossings"));
  std::printf("node model on two_cloths: %d crossings at worst (state %d), %d at the end\n",
              s["crossings"]["max"].get<int>(), s["crossings"]["max_state"].get<int>(),
              s["crossings"]["final"].get<int>());
}

TEST(ImpactZonesCli, TwistedStripCoilsOntoItselfWithoutCrossing) {
  t::TempDir dir;
  nlohmann::json s;
  ASSERT_NO_FATAL_FAILURE(simulate(dir, kTwistedStrip, s));
  expectActedWithoutCrossing(s, 100);  // the strip does touch itself
  // The handle turns 2 cm from the axis and the coil snaps over at up to ~3 cm per step: a
  // response of that order, never metres.
  EXPECT_LT(s["impact_zones"]["max_move"].get<double>(), 0.1);
  std::printf(
      "twisted strip, impact zones: %d zones, %d rigid (failsafe) in %d steps, largest "
      "move %.4f m\n",
      s["impact_zones"]["zones_total"].get<int>(),
      s["impact_zones"]["rigid_zones_total"].get<int>(),
      s["impact_zones"]["rigid_steps"].get<int>(), s["impact_zones"]["max_move"].get<double>());

  // The node model on the same motion: the strip passes through itself.
  t::TempDir nodeDir;
  const std::string scene =
      withSelfCollision(nodeDir, {{"radius", 0.004}, {"friction", 0.3}}, nullptr, kTwistedStrip);
  nlohmann::json ns;
  ASSERT_NO_FATAL_FAILURE(simulate(nodeDir, scene, ns));
  EXPECT_GT(ns["crossings"]["max"].get<int>(), 0);
  std::printf("twisted strip, node model: %d crossings at worst (state %d), in %d states\n",
              ns["crossings"]["max"].get<int>(), ns["crossings"]["max_state"].get<int>(),
              ns["crossings"]["states_with_crossings"].get<int>());
}

TEST(ImpactZonesCli, ClothFoldedOntoItselfNeverCrosses) {
  t::TempDir dir;
  nlohmann::json s;
  ASSERT_NO_FATAL_FAILURE(simulate(dir, kFoldedCloth, s));
  expectActedWithoutCrossing(s, 50);  // the layers are pressed together
  // The fold is laid down slowly: corrections of the thickness's order, no failsafe.
  EXPECT_LT(s["impact_zones"]["max_move"].get<double>(), 0.01);
  EXPECT_EQ(s["impact_zones"]["rigid_zones_total"], 0);
}

TEST(ImpactZonesCli, GradientsThroughImpactZonesAreRefused) {
  t::TempDir dir;
  const nlohmann::json task = {
      {"loss",
       {{"keypoints",
         {{"points", {{{"step", 5}, {"vertices", {0}}, {"positions", {{0.0, 0.4, 0.0}}}}}}}}}},
      {"parameters", {"cloths.0.material.stretch"}}};
  const std::string scene =
      withSelfCollision(dir, {{"model", "impact_zones"}, {"thickness", 0.002}}, task);
  t::expectBadInput("gradient", {scene, "--set", "time.steps=5"}, "cloths.0.self_collision.model",
                    "not implemented");
}

}  // namespace
}  // namespace weft
