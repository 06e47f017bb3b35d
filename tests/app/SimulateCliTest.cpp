// The `weft simulate` contract of the spec, through the real binary: positions.npy, stats.csv,
// rest.obj and summary.json; modules only for the effects a scene names; --set overrides;
// --steps; output folders replaced only on success; reproducible output.

#include "CliSupport.h"

#include <support/SceneBuilder.h>
#include <weft/io/MeshReader.h>
#include <weft/io/Npy.h>
#include <weft/mesh/GridMesh.h>
#include <weft/mesh/RigidTransform.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::dataFile;
using test::describe;
using test::readFile;
using test::runWeft;
using test::TempDir;
using ::testing::StartsWith;

const std::string kHanging = dataFile("scenes/hanging.json");           // 25 vertices, no wind
const std::string kHangingWind = dataFile("scenes/hanging_wind.json");  // the same in wind

nlohmann::json readJson(const std::string& path) {
  return nlohmann::json::parse(readFile(path));
}

std::set<std::string> moduleNames(const nlohmann::json& summary) {
  std::set<std::string> names;
  for (auto it = summary.at("modules").begin(); it != summary.at("modules").end(); ++it)
    names.insert(it.key());
  return names;
}

// Runs a scene and returns the parsed summary.json (empty on failure, with the test failed).
nlohmann::json simulateScene(const std::string& scene, const std::string& out,
                             std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"simulate", scene, "--out", out, "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const test::ProcessResult r = runWeft(args);
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  if (r.exitCode != 0) return {};
  return readJson(out + "/summary.json");
}

TEST(SimulateCli, WritesPositionsNpyInTheContractLayout) {
  TempDir dir;
  const std::string out = dir.file("run");
  const test::ProcessResult r =
      runWeft({"simulate", kHanging, "--steps", "7", "--out", out, "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const test::ParsedNpy npy = test::parseNpy(readFile(out + "/positions.npy"));
  EXPECT_EQ(npy.major, 1);
  EXPECT_EQ(npy.dataOffset % 64, 0u) << "NumPy aligns the data to 64 bytes";
  EXPECT_EQ(npy.shape, (std::vector<std::size_t>{8, 25, 3}));  // steps + 1, vertices, xyz
  ASSERT_EQ(npy.data.size(), 8u * 25u * 3u);

  // Frame 0 is the rest mesh in scene order: the grid convention, rotated and translated.
  TriangleMesh grid = makeGrid(0.4, 0.4, 4, 4);
  RigidTransform t;
  t.rotateDeg = Vec3(90, 0, 0);
  t.translate = Vec3(0, 1, 0);
  t.applyTo(grid.vertices);
  for (int i = 0; i < 25; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(npy.data[i * 3 + c], grid.vertices(i, c)) << "vertex " << i;

  // The same run in the library gives the same bytes: the CLI writes the library's trajectory.
  omp_set_num_threads(1);
  const Scene scene = loadScene(kHanging);
  Simulator sim(scene);
  Trajectory trajectory;
  sim.run(7, trajectory);
  const std::vector<double> expected = trajectory.flattenedPositions();
  ASSERT_EQ(expected.size(), npy.data.size());
  EXPECT_EQ(std::memcmp(expected.data(), npy.data.data(), expected.size() * sizeof(double)), 0);
  // And the engine's own reader agrees with this independent parse.
  const NpyArray again = readNpy(out + "/positions.npy");
  EXPECT_EQ(again.shape, npy.shape);
  EXPECT_EQ(again.data, npy.data);
}

TEST(SimulateCli, WritesStatsCsvWithOneRowPerStep) {
  TempDir dir;
  const std::string out = dir.file("run");
  const nlohmann::json summary = simulateScene(kHangingWind, out, {"--steps", "9"});
  const std::vector<std::string> lines = test::splitLines(readFile(out + "/stats.csv"));
  ASSERT_EQ(lines.size(), 10u) << "header + one row per step";
  const std::vector<std::string> header = test::splitCommas(lines[0]);
  for (const char* column : {"step", "time", "contacts_takeoff", "contacts_stick", "contacts_slip",
                             "pd_iterations", "residual", "converged", "depth"})
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  // Seconds per module: one column for each module the summary lists.
  for (const std::string& module : moduleNames(summary))
    EXPECT_NE(std::find(header.begin(), header.end(), "seconds_" + module), header.end()) << module;
  const auto column = [&](const char* name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (std::size_t row = 1; row < lines.size(); ++row) {
    const std::vector<std::string> f = test::splitCommas(lines[row]);
    ASSERT_EQ(f.size(), header.size()) << lines[row];
    EXPECT_EQ(std::stoi(f[column("step")]), static_cast<int>(row));
    EXPECT_NEAR(std::stod(f[column("time")]), 0.01 * row, 1e-9);
    EXPECT_GE(std::stoi(f[column("pd_iterations")]), 1);
    EXPECT_GE(std::stod(f[column("residual")]), 0.0);
    for (const char* c : {"contacts_takeoff", "contacts_stick", "contacts_slip"})
      EXPECT_EQ(f[column(c)], "0");
    // The cloth hangs from two corners and stretches under gravity: its area grows, by well
    // under a percent at this stiffness.
    const double area = std::stod(f[column("area_ratio")]);
    EXPECT_GT(area, 1.0);
    EXPECT_LT(area, 1.01);
  }
  // summary.json: the area ratio's range over the states (state 0, the rest shape, included).
  ASSERT_TRUE(summary.contains("area_ratio"));
  EXPECT_EQ(summary["area_ratio"]["min"].get<double>(), 1.0);
  EXPECT_GT(summary["area_ratio"]["max"].get<double>(), 1.0);
  EXPECT_NEAR(summary["area_ratio"]["final"].get<double>(),
              std::stod(test::splitCommas(lines.back())[column("area_ratio")]), 1e-8);
}

TEST(SimulateCli, WritesRestObjWithTopology) {
  TempDir dir;
  const std::string out = dir.file("run");
  simulateScene(kHanging, out, {"--steps", "1"});
  const TriangleMesh rest = readMesh(out + "/rest.obj");  // what a user's tool would read
  EXPECT_EQ(rest.vertexCount(), 25);
  EXPECT_EQ(rest.triangleCount(), 32);
  const Scene scene = loadScene(kHanging);
  EXPECT_EQ(rest.triangles, scene.cloths[0].mesh.triangles);
  EXPECT_NEAR((rest.vertices - scene.cloths[0].mesh.vertices).cwiseAbs().maxCoeff(), 0.0, 1e-15);
}

TEST(SimulateCli, WritesSummaryJsonWithTheContractKeys) {
  TempDir dir;
  const std::string out = dir.file("run");
  const nlohmann::json s = simulateScene(kHanging, out, {"--steps", "5"});
  ASSERT_TRUE(s.is_object());
  EXPECT_EQ(s.at("steps"), 5);
  EXPECT_EQ(s.at("vertices"), 25);
  EXPECT_TRUE(s.at("seconds").is_number());
  EXPECT_GT(s.at("seconds").get<double>(), 0.0);
  ASSERT_TRUE(s.at("modules").is_object());
  for (auto it = s["modules"].begin(); it != s["modules"].end(); ++it) {
    EXPECT_TRUE(it.value().is_number()) << it.key();
    EXPECT_GE(it.value().get<double>(), 0.0) << it.key();
  }
  ASSERT_TRUE(s.at("contacts").is_object());
  for (const char* branch : {"takeoff", "stick", "slip"}) {
    ASSERT_TRUE(s["contacts"].contains(branch)) << branch;
    EXPECT_EQ(s["contacts"][branch], 0) << "no contact in this scene";
  }
}

TEST(SimulateCli, BuildsOnlyTheModulesTheSceneNames) {
  TempDir dir;
  const std::set<std::string> plain =
      moduleNames(simulateScene(kHanging, dir.file("plain"), {"--steps", "2"}));
  EXPECT_EQ(plain.count("wind"), 0u) << "no wind in the scene, no wind module";
  EXPECT_EQ(plain.count("gravity"), 1u);
  EXPECT_EQ(plain.count("stretch"), 1u);
  EXPECT_EQ(plain.count("bending"), 1u);
  EXPECT_EQ(plain.count("attachments"), 1u);
  EXPECT_EQ(plain.count("handles"), 0u);
  EXPECT_EQ(plain.count("external_forces"), 0u);

  const std::set<std::string> windy =
      moduleNames(simulateScene(kHangingWind, dir.file("windy"), {"--steps", "2"}));
  EXPECT_EQ(windy.count("wind"), 1u);

  // Without gravity, bending and pins, none of those modules exist either; nodal forces and
  // handles appear when named.
  nlohmann::json doc = test::gridScene(0.4, 3, 0.01, 2, 100.0, 0.0);
  const std::string bare = test::writeScene(dir.file("bare.json"), doc);
  const std::set<std::string> minimal = moduleNames(simulateScene(bare, dir.file("bare")));
  EXPECT_EQ(minimal, (std::set<std::string>{"solver", "stretch"}));

  doc["cloths"][0]["forces"] = {{{"vertices", {5}}, {"force", {0, 0, 0.01}}}};
  doc["cloths"][0]["attachments"] = {
      {{"vertices", {0}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0}, {"offset", {0, 0, 0}}}, {{"time", 1}, {"offset", {0, 1, 0}}}}}}}}};
  const std::string driven = test::writeScene(dir.file("driven.json"), doc);
  EXPECT_EQ(moduleNames(simulateScene(driven, dir.file("driven"))),
            (std::set<std::string>{"solver", "stretch", "handles", "external_forces"}));
}

// A falling, unattached cloth: frame 1 is x0 + g h^2 (implicit Euler from rest).
std::string freeFallScene(const TempDir& dir) {
  nlohmann::json doc = test::gridScene(0.4, 2, 0.01, 3, 200.0);
  doc["gravity"] = {0, -9.8, 0};
  return test::writeScene(dir.file("fall.json"), doc);
}

TEST(SimulateCli, SetOverridesAScalar) {
  TempDir dir;
  const std::string scene = freeFallScene(dir);
  const nlohmann::json s = simulateScene(scene, dir.file("run"), {"--set", "time.dt=0.005"});
  EXPECT_EQ(s.at("dt"), 0.005);
  const NpyArray p = readNpy(dir.file("run/positions.npy"));
  ASSERT_EQ(p.shape, (std::vector<std::size_t>{4, 9, 3}));
  // Frame 1 of vertex 0, y: dropped by g h^2 with the overridden h.
  EXPECT_NEAR(p.data[9 * 3 + 1] - p.data[1], -9.8 * 0.005 * 0.005, 1e-12);
  // The run folder's scene.json is the scene as simulated.
  EXPECT_EQ(readJson(dir.file("run/scene.json"))["time"]["dt"], 0.005);
}

TEST(SimulateCli, SetOverridesAVectorInBothSpellings) {
  TempDir dir;
  const std::string scene = freeFallScene(dir);
  for (const char* value : {"gravity=[0,0,0]", "gravity=0,0,0"}) {
    SCOPED_TRACE(value);
    simulateScene(scene, dir.file("run"), {"--set", value});
    const NpyArray p = readNpy(dir.file("run/positions.npy"));
    ASSERT_EQ(p.shape[0], 4u);
    double largest = 0.0;
    for (std::size_t k = 9 * 3; k < p.data.size(); ++k)
      largest = std::max(largest, std::abs(p.data[k] - p.data[k % 27]));
    EXPECT_LT(largest, 1e-12) << "no gravity, no motion";
  }
  // And a non-zero override is used, not ignored: sideways gravity moves the cloth along X.
  simulateScene(scene, dir.file("run"), {"--set", "gravity=[1,0,0]"});
  const NpyArray p = readNpy(dir.file("run/positions.npy"));
  EXPECT_NEAR(p.data[9 * 3] - p.data[0], 1.0 * 0.01 * 0.01, 1e-12);
}

TEST(SimulateCli, StepsOptionOverridesTheScene) {
  TempDir dir;
  EXPECT_EQ(simulateScene(kHanging, dir.file("a"), {"--steps", "3"}).at("steps"), 3);
  EXPECT_EQ(simulateScene(kHanging, dir.file("b")).at("steps"), 20);  // time.steps of the file
  const nlohmann::json zero = simulateScene(kHanging, dir.file("c"), {"--steps", "0"});
  EXPECT_EQ(zero.at("steps"), 0);
  EXPECT_EQ(readNpy(dir.file("c/positions.npy")).shape, (std::vector<std::size_t>{1, 25, 3}));
  EXPECT_EQ(test::splitLines(readFile(dir.file("c/stats.csv"))).size(), 1u);
}

TEST(SimulateCli, PrintsOneSummaryLineAndDefaultsToOutSceneName) {
  TempDir dir;
  const test::ProcessResult r = runWeft({"simulate", kHanging, "--steps", "2"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = test::splitLines(r.out);
  ASSERT_EQ(lines.size(), 1u) << r.out;
  EXPECT_THAT(lines[0], StartsWith("simulate: hanging: 2 steps, 25 vertices"));
  EXPECT_TRUE(fs::exists(dir.file("out/hanging/positions.npy")));
}

TEST(SimulateCli, SuccessReplacesAnExistingOutputFolderWhole) {
  TempDir dir;
  dir.write("run/stale.txt", "from an older run");
  simulateScene(kHanging, dir.file("run"), {"--steps", "1"});
  EXPECT_FALSE(fs::exists(dir.file("run/stale.txt")));
  EXPECT_TRUE(fs::exists(dir.file("run/positions.npy")));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(SimulateCli, SameSceneTwiceGivesIdenticalFiles) {
  TempDir dir;
  for (const char* threads : {"1", "2"}) {
    SCOPED_TRACE(std::string(threads) + " threads");
    simulateScene(kHangingWind, dir.file("a"), {"--steps", "30", "--threads", threads});
    simulateScene(kHangingWind, dir.file("b"), {"--steps", "30", "--threads", threads});
    EXPECT_EQ(readFile(dir.file("a/positions.npy")), readFile(dir.file("b/positions.npy")));
    EXPECT_EQ(readFile(dir.file("a/rest.obj")), readFile(dir.file("b/rest.obj")));
  }
}

TEST(SimulateCli, FileMeshKeepsItsVertexOrder) {
  TempDir dir;
  // A PLY strip whose faces list vertices out of order, with one pinned vertex.
  dir.write("strip.ply",
            "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty "
            "float z\n"
            "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
            "0.2 0 0.1\n0 0 0\n0.1 0 0.1\n0.2 0 0\n0 0 0.1\n0.1 0 0\n"
            "3 1 4 5\n3 5 4 2\n3 5 2 3\n3 3 2 0\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 2, 100.0);
  doc["cloths"][0]["mesh"] = {{"file", "strip.ply"}};
  doc["gravity"] = {0, -9.8, 0};
  doc["cloths"][0]["attachments"] = {{{"vertices", {3}}}};
  const nlohmann::json s =
      simulateScene(test::writeScene(dir.file("scene.json"), doc), dir.file("run"));
  EXPECT_EQ(s.at("vertices"), 6);
  const NpyArray p = readNpy(dir.file("run/positions.npy"));
  const double expected[6][3] = {{0.2, 0, 0.1}, {0, 0, 0},   {0.1, 0, 0.1},
                                 {0.2, 0, 0},   {0, 0, 0.1}, {0.1, 0, 0}};
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(p.data[i * 3 + c], expected[i][c], 1e-7) << "vertex " << i;
}

TEST(SimulateCli, MeshWarningsArePrintedAndTheRunGoesOn) {
  TempDir dir;
  dir.write("fin.obj",
            "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 1 0.5\nf 1 3 2\nf 1 4 3\nf 1 3 5\n");
  nlohmann::json doc = test::gridScene(1.0, 1, 0.01, 2, 100.0);
  doc["cloths"][0]["mesh"] = {{"file", "fin.obj"}};
  const std::string scene = test::writeScene(dir.file("scene.json"), doc);
  const test::ProcessResult r = runWeft({"simulate", scene, "--out", dir.file("run"), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.err, StartsWith("warning: " + scene + ": cloths.0.mesh: "));
  EXPECT_NE(r.err.find("non-manifold edges (vertex pairs 2 (0, 2))"), std::string::npos) << r.err;
}

TEST(SimulateCli, NumericalFailureExitsThreeNamingStepAndModule) {
  TempDir dir;
  nlohmann::json doc = test::gridScene(0.4, 2, 0.01, 5, 100.0);
  doc["cloths"][0]["initial_velocity"] = {1e6, 0, 0};  // beyond any physical cloth speed
  const std::string scene = test::writeScene(dir.file("scene.json"), doc);
  const test::ProcessResult r = runWeft({"simulate", scene, "--out", dir.file("run"), "--quiet"});
  EXPECT_EQ(r.exitCode, 3) << describe(r);
  EXPECT_THAT(r.err, StartsWith("error: numerical failure: step 1: solver: ")) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("run")));
}

// No silent caps: steps that stop at solver.pd_iterations above the tolerance are counted in
// summary.json, flagged in stats.csv and named on stderr; --strict turns them into exit 3, with
// the run still written for inspection. (Adaptive time stepping off: it would split them.)
TEST(SimulateCli, UnconvergedStepsAreReportedAndStrictExitsThree) {
  TempDir dir;
  nlohmann::json doc = test::hangingClothScene(0.4, 6, 0.01, 8, 800.0, 1e-3);
  doc["solver"] = {
      {"method", "pd"}, {"pd_iterations", 2}, {"pd_tolerance", 1e-8}, {"max_halvings", 0}};
  const std::string scene = test::writeScene(dir.file("scene.json"), doc);
  const test::ProcessResult r = runWeft({"simulate", scene, "--out", dir.file("run"), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const nlohmann::json summary = readJson(dir.file("run/summary.json"));
  const int unconverged = summary["pd"]["unconverged_steps"];
  EXPECT_EQ(unconverged, 8);
  EXPECT_EQ(summary["pd"]["iteration_limit"], 2);
  const std::vector<std::string> lines = test::splitLines(readFile(dir.file("run/stats.csv")));
  const std::vector<std::string> header = test::splitCommas(lines[0]);
  const auto converged = std::find(header.begin(), header.end(), "converged") - header.begin();
  int zeros = 0;
  for (std::size_t k = 1; k < lines.size(); ++k)
    zeros += test::splitCommas(lines[k])[std::size_t(converged)] == "0";
  EXPECT_EQ(zeros, unconverged);
  EXPECT_NE(r.err.find("warning: 8 of 8 steps stopped at the iteration limit "
                       "(solver.pd_iterations 2)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("at step " + std::to_string(int(summary["pd"]["worst_unconverged_step"]))),
            std::string::npos)
      << r.err;

  const test::ProcessResult strict =
      runWeft({"simulate", scene, "--out", dir.file("strict"), "--quiet", "--strict"});
  EXPECT_EQ(strict.exitCode, 3) << describe(strict);
  EXPECT_NE(strict.err.find("error: numerical failure: step "), std::string::npos) << strict.err;
  EXPECT_NE(strict.err.find(": solver: residual "), std::string::npos) << strict.err;
  EXPECT_TRUE(fs::exists(dir.file("strict/summary.json")));

  // A converged run says nothing, also with --strict.
  const test::ProcessResult fine =
      runWeft({"simulate", kHanging, "--out", dir.file("fine"), "--quiet", "--strict"});
  EXPECT_EQ(fine.exitCode, 0) << describe(fine);
  EXPECT_EQ(fine.err.find("warning:"), std::string::npos) << fine.err;
  EXPECT_EQ(readJson(dir.file("fine/summary.json"))["pd"]["unconverged_steps"], 0);
}

// The contact solve's own guard: a plane that slides along itself at 1e310 m/s in its first step
// (the speed overflows to infinity) gives its contacts a non-finite surface velocity; no impulse
// of that may reach contact_forces.npy.
TEST(SimulateCli, NonFiniteContactExitsThreeNamingTheContactSolve) {
  TempDir dir;
  nlohmann::json doc = test::gridScene(0.4, 2, 0.01, 3, 100.0);
  doc["gravity"] = {0.0, -9.8, 0.0};
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 0.001, 0.0}}};
  doc["obstacles"] = {{{"plane", {{"point", {0.0, 0.0, 0.0}}, {"normal", {0.0, 1.0, 0.0}}}},
                       {"friction", 0.3},
                       {"motion",
                        {{"keyframes",
                          {{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}},
                           {{"time", 0.01}, {"offset", {1e308, 0.0, 0.0}}}}}}}}};
  const std::string scene = test::writeScene(dir.file("scene.json"), doc);
  const test::ProcessResult r = runWeft({"simulate", scene, "--out", dir.file("run"), "--quiet"});
  EXPECT_EQ(r.exitCode, 3) << describe(r);
  EXPECT_THAT(r.err, StartsWith("error: numerical failure: step 1: contact_solve: non-finite "
                                "contact impulse or velocity"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir.file("run")));
}

TEST(SimulateCli, UsageErrorsExitTwo) {
  TempDir dir;
  const test::ProcessResult none = runWeft({});
  EXPECT_EQ(none.exitCode, 2) << describe(none);
  const test::ProcessResult verb = runWeft({"simulat", kHanging});
  EXPECT_EQ(verb.exitCode, 2) << describe(verb);
  EXPECT_THAT(verb.err, StartsWith("error: weft: simulat: unknown verb"));
  const test::ProcessResult help = runWeft({"--help"});
  EXPECT_EQ(help.exitCode, 0) << describe(help);
  EXPECT_NE(help.out.find("simulate SCENE"), std::string::npos);
}

TEST(SimulateCli, ContactTraceNamesWhereEachTracedStepsResidualSits) {
  // WEFT_CONTACT_TRACE=a-b: each traced Newton contact step ends with the nodes holding the largest
  // shares of its mass-weighted squared residual, largest first (scripts/trace-stall-hinges.py
  // reads them); steps outside the range print nothing.
  TempDir dir;
  const test::ProcessResult r =
      test::runProcess({"/usr/bin/env", "WEFT_CONTACT_TRACE=3-4", WEFT_BINARY, "simulate",
                        std::string(WEFT_ASSET_DIR) + "/scenes/slope.json", "--steps", "5", "--out",
                        dir.file("out"), "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  std::vector<int> traced;
  std::map<int, std::vector<double>> shares;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) {
    int step = 0, node = -1;
    double share = -1.0;
    char branch[16] = {};
    if (std::sscanf(line.c_str(), "step %d: newton contact solve", &step) == 1) {
      traced.push_back(step);
    } else if (std::sscanf(line.c_str(),
                           "  residual at node %d: share %lf, x (%*f, %*f, %*f), contact %15s",
                           &node, &share, branch) == 3) {
      ASSERT_FALSE(traced.empty()) << line;
      EXPECT_GE(node, 0);
      EXPECT_LT(node, 25 * 25);
      EXPECT_TRUE(std::string(branch) == "takeoff" || std::string(branch) == "stick" ||
                  std::string(branch) == "slip" || std::string(branch) == "none")
          << line;
      shares[traced.back()].push_back(share);
    }
  }
  EXPECT_EQ(traced, (std::vector<int>{3, 4})) << r.err;
  for (int step : {3, 4}) {
    const std::vector<double>& s = shares[step];
    ASSERT_EQ(s.size(), 8u) << "step " << step << ":\n" << r.err;
    double sum = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      EXPECT_GE(s[i], 0.0);
      if (i > 0) {
        EXPECT_LE(s[i], s[i - 1]) << "largest first";
      }
      sum += s[i];
    }
    EXPECT_GT(s[0], 0.0);
    EXPECT_LE(sum, 1.0 + 1e-9) << "shares of one total";
  }
}

}  // namespace
}  // namespace weft
