// The shipped scenes and the contact benchmarks, through the real binary: every
// assets/scenes/*.json loads and simulates a couple of steps, and `weft bench continuity` and
// `weft bench contact` (and `weft bench backward`) produce their CSV in quick mode (what
// docs/cli.md documents must run).

#include "CliSupport.h"

#include <weft/bench/BackwardBench.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::describe;
using test::readCsv;
using test::readFile;
using test::runWeft;
using test::splitCommas;
using test::splitLines;
using test::TempDir;

std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(std::string(WEFT_ASSET_DIR) + "/scenes"))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());  // a stable order for the failure messages
  return files;
}

TEST(SceneAssets, EverySceneSimulatesTwoSteps) {
  const std::vector<std::string> files = sceneFiles();
  // The paper's scenes of issue 3 plus the default wind scene.
  for (const char* name : {"wind", "slope", "sphere", "bowl", "crumple"})
    EXPECT_TRUE(std::any_of(files.begin(), files.end(),
                            [&](const std::string& f) { return fs::path(f).stem() == name; }))
        << name << ".json is missing from assets/scenes";
  TempDir dir;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const std::string out = dir.file(fs::path(file).stem().string());
    const auto r =
        runWeft({"simulate", file, "--steps", "2", "--out", out, "--quiet", "--threads", "1"});
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_TRUE(fs::exists(out + "/positions.npy"));
    EXPECT_EQ(splitLines(readFile(out + "/stats.csv")).size(), 3u);  // header and two steps
    // Exactly the contact modules the scene names are built (and the others are not).
    const nlohmann::json scene = nlohmann::json::parse(readFile(file));
    const nlohmann::json modules =
        nlohmann::json::parse(readFile(out + "/summary.json"))["modules"];
    bool selfCollision = false, impactZones = false;
    for (const auto& cloth : scene["cloths"]) {
      if (!cloth.contains("self_collision")) continue;
      // self_collision.model: "node" (the default), "impact_zones", or a list of both.
      const nlohmann::json model =
          cloth["self_collision"].value("model", nlohmann::json::array({"node"}));
      const auto names = model.is_array() ? model : nlohmann::json::array({model});
      for (const auto& name : names) {
        selfCollision = selfCollision || name == "node";
        impactZones = impactZones || name == "impact_zones";
      }
    }
    const bool obstacles = scene.contains("obstacles") && !scene["obstacles"].empty();
    EXPECT_EQ(modules.contains("contact_detection"), obstacles);
    EXPECT_EQ(modules.contains("self_collision"), selfCollision);
    EXPECT_EQ(modules.contains("impact_zones"), impactZones);
    EXPECT_EQ(modules.contains("contact_solve"), obstacles || selfCollision);
    EXPECT_EQ(modules.contains("wind"), scene.contains("wind"));
  }
}

// The shipped scenes with contact: obstacles or self-collision.
std::vector<std::string> contactSceneFiles() {
  std::vector<std::string> files;
  for (const std::string& file : sceneFiles()) {
    const nlohmann::json scene = nlohmann::json::parse(readFile(file));
    bool selfCollision = false;
    for (const auto& cloth : scene["cloths"])
      selfCollision = selfCollision || cloth.contains("self_collision");
    if (selfCollision || (scene.contains("obstacles") && !scene["obstacles"].empty()))
      files.push_back(file);
  }
  return files;
}

TEST(SceneAssets, ThePapersContactScenesAreShipped) {
  std::vector<std::string> names;
  for (const std::string& file : contactSceneFiles()) names.push_back(fs::path(file).stem());
  for (const char* name : {"bowl", "crumple", "hat", "slope", "sock", "sphere", "tshirt"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

// Issue 36's promise, on each shipped contact scene with its own solver settings, over its first
// 70 steps (Crumple's cloth hits the pyramid's walls at about step 55), the Bowl's first 50 (it
// lands at about step 35, its deepest step; 70 of its steps took a minute with the machine
// shared); the full lengths are scripts/contact-scenes.py's: every step converges at the scene's
// pd_tolerance (--strict exits 3 otherwise) and no node ends a step more than 0.1 mm inside an
// obstacle's skin. One test per scene (the Bowl's alone takes tens of seconds); what each run did
// is printed.
class ContactSceneAsset : public ::testing::TestWithParam<std::string> {};

TEST_P(ContactSceneAsset, ConvergesEveryStepWithoutNodesInsideObstacles) {
  constexpr int kSteps = 70;
  const std::string& file = GetParam();
  const nlohmann::json scene = nlohmann::json::parse(readFile(file));
  const int steps =
      std::min(fs::path(file).stem() == "bowl" ? 50 : kSteps, scene["time"]["steps"].get<int>());
  TempDir dir;
  const std::string out = dir.file("run");
  const auto r = runWeft({"simulate", file, "--steps", std::to_string(steps), "--out", out,
                          "--quiet", "--strict", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const nlohmann::json summary = nlohmann::json::parse(readFile(out + "/summary.json"));
  EXPECT_EQ(summary["pd"]["converged_steps"], steps);
  EXPECT_EQ(summary["pd"]["unconverged_steps"], 0);
  const double depth = summary["contacts"]["max_depth"].get<double>();
  EXPECT_LE(depth, 1e-4) << "at step " << summary["contacts"]["max_depth_step"];
  // Under impact zones (Liang 2019) no edge of a self-colliding cloth passes through a face, at
  // any state; the count is the independent edge-triangle test's.
  if (summary.contains("impact_zones")) {
    EXPECT_EQ(summary["impact_zones"]["unresolved_steps"], 0);
    EXPECT_EQ(summary["crossings"]["max"], 0) << "at state " << summary["crossings"]["max_state"];
  }
  std::printf("%s: %d of %d steps converged, %d split (down to dt/%d), deepest %.4f mm\n",
              fs::path(file).stem().string().c_str(), summary["pd"]["converged_steps"].get<int>(),
              steps, summary["pd"]["split_steps"].get<int>(),
              1 << summary["pd"]["deepest_halvings"].get<int>(), 1e3 * depth);
}

INSTANTIATE_TEST_SUITE_P(SceneAssets, ContactSceneAsset, ::testing::ValuesIn(contactSceneFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return fs::path(info.param).stem().string();
                         });

// DiffCloth's Bowl (Fig. 5): a napkin falling into a bowl. Their point is the area ratio (the
// napkin's area over its rest area): Liang et al.'s contact handling moves nodes out of the
// obstacle without asking whether friction could hold them and the napkin's size jumps ("popping"),
// the Signorini-Coulomb contact keeps it. The shipped scene at 16x16 quads for its first 200
// steps (it lands at about step 40 and slides down the wall): the area stays within 0.5 % of
// rest and changes by under 0.3 % in any one step (measured: 0.9979-1.0002, largest step 0.12 %;
// the full scene, 50x50 over 500 steps, 0.9979-1.0002, largest step 0.10 %, docs/benchmarks.md).
TEST(SceneAssets, BowlKeepsTheNapkinsArea) {
  TempDir dir;
  const std::string out = dir.file("bowl");
  const auto r = runWeft({"simulate", std::string(WEFT_ASSET_DIR) + "/scenes/bowl.json", "--set",
                          "cloths.0.mesh.grid.resolution=[16,16]", "--steps", "200", "--out", out,
                          "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto rows = readCsv(out + "/stats.csv");
  ASSERT_EQ(rows.size(), 201u);
  const auto column = static_cast<std::size_t>(
      std::find(rows[0].begin(), rows[0].end(), "area_ratio") - rows[0].begin());
  ASSERT_LT(column, rows[0].size());
  double previous = 1.0, largestJump = 0.0;
  int landed = 0;
  const auto slip = static_cast<std::size_t>(
      std::find(rows[0].begin(), rows[0].end(), "contacts_slip") - rows[0].begin());
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double area = std::stod(rows[k][column]);
    EXPECT_NEAR(area, 1.0, 5e-3) << "step " << k;
    largestJump = std::max(largestJump, std::abs(area - previous));
    previous = area;
    landed += std::stoi(rows[k][slip]) > 0;
  }
  EXPECT_LT(largestJump, 3e-3);
  EXPECT_GT(landed, 100)
      << "steps with slipping contacts: the napkin should land and slide in the bowl";
  const nlohmann::json summary = nlohmann::json::parse(readFile(out + "/summary.json"));
  EXPECT_NEAR(summary["area_ratio"]["final"].get<double>(), previous, 1e-8);
}

TEST(SceneAssets, ContinuityBenchQuickWritesCsv) {
  TempDir dir;
  const std::string out = dir.file("continuity");
  const auto r = runWeft({"bench", "continuity", "--quick", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto rows = readCsv(out + "/continuity.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0][0], "surface");
  // 5 mu samples x 3 surfaces x 2 steps x 3 nodes.
  EXPECT_EQ(rows.size(), 1u + 5 * 3 * 2 * 3);
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_EQ(rows[i].back(), "0") << "numerical failure in row " << i;
  EXPECT_TRUE(fs::exists(out + "/continuity.md"));
  // On the analytic sphere every step converges and each curve is continuous: halving the mu
  // spacing halves its largest difference (DiffCloth Fig. 2; a jump would keep the ratio near 1).
  const auto summary = readCsv(out + "/continuity_summary.csv");
  ASSERT_EQ(summary.size(), 1u + 3 * 2 * 3);
  ASSERT_EQ(summary[0][7], "halving_ratio");
  ASSERT_EQ(summary[0][9], "unconverged_max");
  int analytic = 0;
  for (std::size_t i = 1; i < summary.size(); ++i) {
    if (summary[i][0] != "analytic") continue;
    ++analytic;
    EXPECT_LT(std::stod(summary[i][7]), 0.6) << "row " << i;
    EXPECT_EQ(summary[i][9], "0") << "row " << i;
  }
  EXPECT_EQ(analytic, 2 * 3);
}

TEST(SceneAssets, ContactBenchQuickWritesCsv) {
  TempDir dir;
  const std::string out = dir.file("contact");
  const auto r = runWeft({"bench", "contact", "--quick", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto rows = readCsv(out + "/contact.csv");
  ASSERT_EQ(rows.size(), 1u + 3 * 2);  // three scenes at two resolutions
  EXPECT_EQ(rows[0][0], "scene");
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) -
                                    rows[0].begin());
  };
  const std::size_t mean = column("ms_per_step"), median = column("ms_median_step");
  ASSERT_LT(mean, rows[0].size());
  ASSERT_LT(median, rows[0].size());
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].back(), "0") << "numerical failure in row " << i;
    EXPECT_GT(std::stod(rows[i][mean]), 0.0) << "ms_per_step, row " << i;
    EXPECT_GT(std::stod(rows[i][median]), 0.0) << "ms_median_step, row " << i;
  }
}

TEST(SceneAssets, BackwardBenchQuickWritesCsv) {
  TempDir dir;
  const std::string out = dir.file("backward");
  const auto r = runWeft({"bench", "backward", "--quick", "--resolutions", "12", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto rows = readCsv(out + "/backward.csv");
  // Wind and Slope: direct, then fixed point and GMRES preconditioned by P, by the clamped Hessian
  // and automatically, each at 1e-4 and 1e-6, and the default: automatic with accuracy 1e-3.
  ASSERT_EQ(rows.size(), 1u + 2 * 10);
  const std::vector<std::string> columns = {"scene",
                                            "quads",
                                            "vertices",
                                            "steps",
                                            "method",
                                            "tolerance",
                                            "backward_s",
                                            "ms_per_step",
                                            "solve_ms_per_step",
                                            "rest_ms_per_step",
                                            "iterations_per_step",
                                            "max_iterations",
                                            "not_converged",
                                            "fallbacks",
                                            "fail_percent",
                                            "speedup_vs_direct",
                                            "gradient_rel_error",
                                            "forward_ms_per_step",
                                            "forward_unconverged",
                                            "peak_rss_mb",
                                            "delta_p_ms_per_step",
                                            "delta_r_ms_per_step",
                                            "fallback_ms_per_step",
                                            "cpu_ms_per_step",
                                            "cpu_speedup_vs_direct",
                                            "adjoint_growth",
                                            "hessian_iterations_per_step",
                                            "hessian_factorizations",
                                            "passes",
                                            "error_estimate"};
  EXPECT_EQ(rows[0], columns);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    // The adjoint's growth over each pass (diff/AdjointGrowth.h): at least 1 by definition.
    EXPECT_GE(std::stod(rows[i][25]), 1.0) << "row " << i;
    // GMRES with the clamped Hessian factors it once per step, and only it iterates with it;
    // P alone never does.
    const int steps = std::stoi(rows[i][3]), factorizations = std::stoi(rows[i][27]);
    if (rows[i][4] == "gmres+hessian") {
      EXPECT_EQ(factorizations, steps) << "row " << i;
    }
    if (rows[i][4] == "gmres" || rows[i][4] == "direct") {
      EXPECT_EQ(factorizations, 0) << "row " << i;
    }
    if (rows[i][4] == "gmres") {
      EXPECT_EQ(std::stod(rows[i][26]), 0.0) << "row " << i;
    }
    // The error-controlled row: at least two passes, its estimate within the accuracy and
    // bounding its error against the direct row's gradient.
    if (rows[i][4] == "gmres+auto accuracy 0.001") {
      EXPECT_GE(std::stoi(rows[i][28]), 2) << "row " << i;
      EXPECT_LE(std::stod(rows[i][29]), 1e-3) << "row " << i;
      EXPECT_LE(std::stod(rows[i][16]), std::stod(rows[i][29]) + 1e-12) << "row " << i;
    } else {
      EXPECT_EQ(rows[i][28], "1") << "row " << i;
    }
  }
  // GMRES at tolerance 1e-6 gives the direct solve's gradient to about 6e-7 on Wind here (1e-5 in
  // the full 200-step run, where errors of the per-step solves accumulate); at 1e-4 about 1e-5.
  // Slope goes through the contact adjoint (every node slipping).
  int gmres = 0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i][4].rfind("gmres", 0) == 0 && rows[i][5] == "1e-06") {
      ++gmres;
      EXPECT_LT(std::stod(rows[i][16]), 1e-5)
          << rows[i][0] << ": GMRES gradient vs direct, row " << i;
    }
  EXPECT_EQ(gmres, 6);
  EXPECT_TRUE(fs::exists(out + "/backward.md"));
}

// `--calibrate` times the clamped Hessian's factorisation and an iteration with it against an
// iteration with P and prints the estimates the automatic preconditioner uses; the estimate
// column must be the formula it states (kFactorCostScale x sqrt(flop_ratio)), and factorising
// costs more flops than an iteration.
TEST(SceneAssets, BackwardBenchCalibrateWritesTheEstimateBesideTheTimings) {
  TempDir dir;
  const std::string out = dir.file("calibrate");
  const auto r = runWeft(
      {"bench", "backward", "--calibrate", "--scenes", "wind", "--resolutions", "8", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto rows = readCsv(out + "/calibrate.csv");
  ASSERT_EQ(rows.size(), 2u);
  const std::vector<std::string> columns = {"scene",
                                            "quads",
                                            "vertices",
                                            "first_factor_ms",
                                            "factor_ms",
                                            "iteration_ms",
                                            "measured_iterations",
                                            "flop_ratio",
                                            "estimated_iterations",
                                            "estimate_over_measured",
                                            "hessian_iteration_ms",
                                            "measured_hessian_iteration_cost",
                                            "estimated_hessian_iteration_cost"};
  ASSERT_EQ(rows[0], columns);
  const auto& row = rows[1];
  EXPECT_EQ(row[1], "8");
  for (std::size_t c = 3; c <= 6; ++c) EXPECT_GT(std::stod(row[c]), 0.0) << columns[c];
  const double flopRatio = std::stod(row[7]);
  EXPECT_GT(flopRatio, 1.0);
  EXPECT_NEAR(std::stod(row[8]), bench::factorCostScale() * std::sqrt(flopRatio),
              1e-2 * std::stod(row[8]));
  // An iteration with H's factor (3m unknowns, one column) does more work than one with P's
  // (m unknowns, three columns): H's L has about 9 times P's entries.
  EXPECT_GT(std::stod(row[10]), 0.0);
  EXPECT_GT(std::stod(row[12]), 1.0);
  EXPECT_TRUE(fs::exists(out + "/calibrate.md"));
  const auto wrong = runWeft({"bench", "contact", "--calibrate", "--out", dir.file("wrong")});
  EXPECT_EQ(wrong.exitCode, 2) << describe(wrong);
  EXPECT_NE(wrong.err.find("--calibrate: applies to the backward benchmark only"),
            std::string::npos)
      << describe(wrong);
}

}  // namespace
}  // namespace weft
