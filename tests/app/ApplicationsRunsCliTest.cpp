// `weft bench applications`: runs written as they finish and --resume (through the real binary),
// and the garment tasks on the DiffCloth release's meshes (--paper-meshes; the scenes are built
// in-process with the bench's own PaperMeshScenes.h and simulated a few steps). The paper-mesh
// tests skip when ../shared/meshes/diffcloth is absent.

#include <app/CliSupport.h>

#include <weft/bench/PaperMeshScenes.h>
#include <weft/io/Npy.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace weft {
namespace {

namespace fs = std::filesystem;
using test::describe;
using test::runWeft;
using test::splitCommas;
using test::splitLines;
using test::TempDir;

const std::vector<std::string> kMethods = {"lbfgsb", "cmaes", "es1p1"};

// The applications.csv rows of one run file (header dropped).
std::vector<std::string> runRows(const std::string& file) {
  auto lines = splitLines(test::readFile(file));
  EXPECT_FALSE(lines.empty()) << file;
  if (!lines.empty()) {
    EXPECT_EQ(lines[0], "task,method,seed,evaluation,steps,wall_s,loss");
    lines.erase(lines.begin());
  }
  return lines;
}

// Replaces the loss of the last row of a run file.
void editLastLoss(const std::string& file, const std::string& loss) {
  auto lines = splitLines(test::readFile(file));
  ASSERT_GE(lines.size(), 2u);
  auto f = splitCommas(lines.back());
  ASSERT_EQ(f.size(), 7u);
  f[6] = loss;
  std::string edited;
  for (std::size_t i = 0; i < f.size(); ++i) edited += (i ? "," : "") + f[i];
  lines.back() = edited;
  std::ofstream out(file, std::ios::trunc);
  for (const auto& l : lines) out << l << "\n";
}

TEST(ApplicationsRunsCli, EveryRunIsStoredAndResumeReadsItBack) {
  TempDir dir;
  const std::string out = dir.file("bench");
  const std::vector<std::string> args = {
      "bench",    "applications", "--quick", "--tasks", "napkin_4x4", "--seeds", "1",
      "--budget", "450",          "--out",   out,       "--threads",  "1"};
  const auto first = runWeft(args);
  ASSERT_EQ(first.exitCode, 0) << describe(first);
  EXPECT_FALSE(fs::exists(out + ".partial")) << "the run store is folded into DIR/runs";
  // One file per run; applications.csv is exactly their rows, run after run.
  std::vector<std::string> all = {"task,method,seed,evaluation,steps,wall_s,loss"};
  for (const auto& m : kMethods) {
    const std::string file = out + "/runs/napkin_4x4_" + m + "_1.csv";
    ASSERT_TRUE(fs::exists(file)) << file;
    const auto rows = runRows(file);
    ASSERT_FALSE(rows.empty()) << file;
    for (const auto& row : rows) {
      const auto f = splitCommas(row);
      ASSERT_EQ(f.size(), 7u);
      EXPECT_EQ(f[1], m);
      EXPECT_LE(std::stoll(f[4]), 450);  // within the budget
    }
    all.insert(all.end(), rows.begin(), rows.end());
  }
  const std::string csv = test::readFile(out + "/applications.csv");
  EXPECT_EQ(splitLines(csv), all);
  // Each run's parameters at each evaluation, one row per row of its run file; the three methods
  // start from the seed's one starting point (Table 2: the same initial seed set).
  std::vector<std::string> firstRows;
  for (const auto& m : kMethods) {
    const std::string file = out + "/runs/parameters/napkin_4x4_" + m + "_1.csv";
    ASSERT_TRUE(fs::exists(file)) << file;
    auto lines = splitLines(test::readFile(file));
    const auto rows = runRows(out + "/runs/napkin_4x4_" + m + "_1.csv");
    ASSERT_EQ(lines.size(), rows.size() + 1) << file;
    const auto header = splitCommas(lines[0]);
    EXPECT_EQ(header.size(), 1u + 48u) << lines[0];  // 4x4 nodes, a force each (48 DoF)
    EXPECT_EQ(header[0], "evaluation");
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const auto f = splitCommas(lines[r + 1]);
      ASSERT_EQ(f.size(), header.size()) << file << " row " << r + 1;
      EXPECT_EQ(f[0], splitCommas(rows[r])[3]) << file;  // the same evaluation
      for (std::size_t i = 1; i < f.size(); ++i) EXPECT_TRUE(std::isfinite(std::stod(f[i])));
    }
    firstRows.push_back(lines[1]);
  }
  EXPECT_EQ(firstRows[1], firstRows[0]);
  EXPECT_EQ(firstRows[2], firstRows[0]);
  const std::string settings = test::readFile(out + "/runs/settings.json");
  EXPECT_NE(settings.find("\"budget\": 450"), std::string::npos) << settings;
  EXPECT_NE(settings.find("\"quick\": true"), std::string::npos) << settings;
  EXPECT_NE(settings.find("\"paper_meshes\": null"), std::string::npos) << settings;

  // Resumed: nothing is run again, the tables come out the same.
  auto again = args;
  again.push_back("--resume");
  const auto second = runWeft(again);
  ASSERT_EQ(second.exitCode, 0) << describe(second);
  EXPECT_NE(second.out.find("0 run(s) made, 3 resumed"), std::string::npos) << second.out;
  EXPECT_EQ(second.err.find("napkin_4x4, lbfgsb, seed 1..."), std::string::npos) << second.err;
  EXPECT_EQ(test::readFile(out + "/applications.csv"), csv);

  // A stored run is read, not recomputed: an edited loss comes through to the tables.
  editLastLoss(out + "/runs/napkin_4x4_cmaes_1.csv", "1.25e-99");
  const auto third = runWeft(again);
  ASSERT_EQ(third.exitCode, 0) << describe(third);
  const std::string edited = test::readFile(out + "/applications.csv");
  EXPECT_NE(edited.find("napkin_4x4,cmaes,1,"), std::string::npos);
  EXPECT_NE(edited.find(",1.25e-99\n"), std::string::npos) << edited;
  EXPECT_NE(test::readFile(out + "/applications.md").find("1.25e-99"), std::string::npos);

  // More seeds extend the finished comparison: only seed 2's runs are made.
  auto more = again;
  more[6] = "2";
  const auto fourth = runWeft(more);
  ASSERT_EQ(fourth.exitCode, 0) << describe(fourth);
  EXPECT_NE(fourth.out.find("3 run(s) made, 3 resumed"), std::string::npos) << fourth.out;
  for (const auto& m : kMethods) {
    EXPECT_TRUE(fs::exists(out + "/runs/napkin_4x4_" + m + "_2.csv"));
    EXPECT_TRUE(fs::exists(out + "/runs/parameters/napkin_4x4_" + m + "_2.csv"));
    EXPECT_TRUE(fs::exists(out + "/runs/parameters/napkin_4x4_" + m + "_1.csv"))
        << "carried over from the finished comparison";
  }
}

// A run file's (or applications.csv's) rows without the wall-clock column, which depends on
// the load.
std::vector<std::string> withoutWallSeconds(const std::string& file) {
  std::vector<std::string> rows;
  for (const auto& row : runRows(file)) {
    auto f = splitCommas(row);
    if (f.size() == 7u) f.erase(f.begin() + 5);
    std::string joined;
    for (std::size_t i = 0; i < f.size(); ++i) joined += (i ? "," : "") + f[i];
    rows.push_back(joined);
  }
  return rows;
}

TEST(ApplicationsRunsCli, RunsMadeTwoAtATimeAreTheRunsMadeOneAtATime) {
  // --jobs 2 runs the six (method, seed) runs on two threads; each run is the same as when the
  // runs are made one after another: the same evaluations, losses and parameter values.
  TempDir dir;
  std::vector<std::string> args = {"bench",      "applications", "--quick", "--tasks",
                                   "napkin_4x4", "--seeds",      "2",       "--budget",
                                   "450",        "--threads",    "1",       "--out"};
  auto one = args, two = args;
  one.push_back(dir.file("one"));
  two.insert(two.end(), {dir.file("two"), "--jobs", "2"});
  const auto serial = runWeft(one);
  ASSERT_EQ(serial.exitCode, 0) << describe(serial);
  const auto parallel = runWeft(two);
  ASSERT_EQ(parallel.exitCode, 0) << describe(parallel);
  EXPECT_NE(parallel.out.find("6 run(s) made"), std::string::npos) << parallel.out;
  EXPECT_NE(test::readFile(dir.file("two") + "/applications.md").find("2 run(s) at a time"),
            std::string::npos);
  for (const auto& m : kMethods)
    for (const char* seed : {"1", "2"}) {
      const std::string name = "napkin_4x4_" + m + "_" + seed + ".csv";
      const auto a = withoutWallSeconds(dir.file("one") + "/runs/" + name);
      ASSERT_FALSE(a.empty()) << name;
      EXPECT_EQ(withoutWallSeconds(dir.file("two") + "/runs/" + name), a) << name;
      EXPECT_EQ(test::readFile(dir.file("two") + "/runs/parameters/" + name),
                test::readFile(dir.file("one") + "/runs/parameters/" + name))
          << name;
    }
  // applications.csv (the run files' columns) lists the same rows in the same order.
  EXPECT_EQ(withoutWallSeconds(dir.file("two") + "/applications.csv"),
            withoutWallSeconds(dir.file("one") + "/applications.csv"));
}

TEST(ApplicationsRunsCli, AKilledComparisonKeepsItsFinishedRunsAndResumeContinuesIt) {
  TempDir dir;
  const std::string out = dir.file("bench");
  const std::string store = out + ".partial";
  std::vector<std::string> args = {WEFT_BINARY, "bench",      "applications", "--quick",
                                   "--tasks",   "napkin_4x4", "--seeds",      "3",
                                   "--out",     out,          "--threads",    "1"};
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int devnull = ::open("/dev/null", O_WRONLY);
    dup2(devnull, 1), dup2(devnull, 2);
    execv(argv[0], argv.data());
    _exit(127);
  }
  // Killed as soon as its first run is stored.
  const std::string firstRun = store + "/napkin_4x4_lbfgsb_1.csv";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(firstRun) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(fs::exists(firstRun)) << "no run stored within 60 s";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the comparison finished before it could be killed";
  EXPECT_FALSE(fs::exists(out)) << "no tables from a killed comparison";
  const std::string stored = test::readFile(firstRun);
  const auto rows = runRows(firstRun);
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(splitCommas(rows.back())[4], std::to_string(50 * 2 * rows.size()))
      << "a whole L-BFGS-B run: 100 steps per gradient evaluation";

  // Without --resume the stored runs are not overwritten.
  std::vector<std::string> plain(args.begin() + 1, args.end());
  const auto refused = runWeft(plain);
  EXPECT_EQ(refused.exitCode, 2) << describe(refused);
  EXPECT_NE(refused.err.find(store + ": --resume: "), std::string::npos) << refused.err;
  EXPECT_EQ(test::readFile(firstRun), stored);

  // With a different budget, --resume is refused and the store kept.
  auto otherBudget = plain;
  otherBudget.insert(otherBudget.end(), {"--resume", "--budget", "900"});
  const auto mismatch = runWeft(otherBudget);
  EXPECT_EQ(mismatch.exitCode, 2) << describe(mismatch);
  EXPECT_EQ(mismatch.err.rfind("error: " + store + "/settings.json: budget: ", 0), 0u)
      << mismatch.err;
  EXPECT_NE(mismatch.err.find("--budget 900"), std::string::npos) << mismatch.err;
  EXPECT_TRUE(fs::exists(store));

  auto resumed = plain;
  resumed.push_back("--resume");
  const auto r = runWeft(resumed);
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_FALSE(fs::exists(store));
  // The stored run is taken as it was (its wall-clock column too, which a rerun would change).
  EXPECT_EQ(test::readFile(out + "/runs/napkin_4x4_lbfgsb_1.csv"), stored);
  EXPECT_EQ(r.err.find("napkin_4x4, lbfgsb, seed 1..."), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("napkin_4x4, es1p1, seed 3..."), std::string::npos) << r.err;
  int runs = 0;
  for (const auto& e : fs::directory_iterator(out + "/runs"))
    runs += e.path().extension() == ".csv";
  EXPECT_EQ(runs, 9);
}

// The cells of the markdown rows of `task` in applications.md, table after table (losses, steps,
// passes, ...), each row's cells trimmed.
std::vector<std::vector<std::string>> taskRows(const std::string& md, const std::string& task) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& line : splitLines(md)) {
    if (line.rfind("| " + task + " |", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream items(line.substr(1));
    for (std::string cell; std::getline(items, cell, '|');) {
      const auto a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    rows.push_back(cells);
  }
  return rows;
}

TEST(ApplicationsRunsCli, MethodsMakesOnlyTheNamedMethodsRunsAndResumeAddsTheOthers) {
  TempDir dir;
  const std::string out = dir.file("bench");
  std::vector<std::string> args = {
      "bench",    "applications", "--quick", "--tasks", "napkin_4x4", "--seeds", "1",
      "--budget", "450",          "--out",   out,       "--threads",  "1",       "--methods"};
  auto first = args;
  first.push_back("es1p1");
  const auto es = runWeft(first);
  ASSERT_EQ(es.exitCode, 0) << describe(es);
  EXPECT_NE(es.out.find("1 run(s) made, 0 resumed"), std::string::npos) << es.out;
  EXPECT_FALSE(fs::exists(out + "/runs/napkin_4x4_lbfgsb_1.csv"));
  EXPECT_FALSE(fs::exists(out + "/runs/napkin_4x4_cmaes_1.csv"));
  const std::string esRun = out + "/runs/napkin_4x4_es1p1_1.csv";
  ASSERT_TRUE(fs::exists(esRun));
  const std::string esStored = test::readFile(esRun);
  // The methods without runs show "-", not "> budget" (which would claim they ran and failed).
  auto rows = taskRows(test::readFile(out + "/applications.md"), "napkin_4x4");
  ASSERT_GE(rows.size(), 2u);
  const auto& losses = rows[0];  // task, parameters, seeds, budget, min initial, L-BFGS-B final %
  ASSERT_GE(losses.size(), 10u);
  EXPECT_EQ(losses[5], "-");
  EXPECT_EQ(losses[6], "-");
  EXPECT_NE(losses[8], "-");    // (1+1)-ES final %
  const auto& steps = rows[1];  // task, parameters, threshold, 3 conv. steps, 3 to threshold, ...
  ASSERT_GE(steps.size(), 11u);
  EXPECT_EQ(steps[3], "-");
  EXPECT_EQ(steps[4], "-");
  EXPECT_NE(steps[5], "-");
  EXPECT_EQ(steps[6], "-");
  EXPECT_EQ(steps[7], "-");
  EXPECT_EQ(steps[9], "-");  // no speedup without L-BFGS-B
  EXPECT_EQ(steps[10], "-");

  // The other two are added to the finished comparison; the (1+1)-ES run is read back.
  auto rest = args;
  rest.insert(rest.end(), {"lbfgsb,cmaes", "--resume"});
  const auto more = runWeft(rest);
  ASSERT_EQ(more.exitCode, 0) << describe(more);
  EXPECT_NE(more.out.find("2 run(s) made, 1 resumed"), std::string::npos) << more.out;
  EXPECT_EQ(test::readFile(esRun), esStored);
  for (const auto& m : kMethods) EXPECT_TRUE(fs::exists(out + "/runs/napkin_4x4_" + m + "_1.csv"));
  rows = taskRows(test::readFile(out + "/applications.md"), "napkin_4x4");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_NE(rows[0][5], "-");
  EXPECT_NE(rows[1][3], "-");

  auto unknown = args;
  unknown.push_back("lbfgsb,bfgs");
  const auto bad = runWeft(unknown);
  EXPECT_EQ(bad.exitCode, 2) << describe(bad);
  EXPECT_NE(bad.err.find("--methods: unknown method 'bfgs'"), std::string::npos) << bad.err;
}

TEST(ApplicationsRunsCli, PaperMeshesNeedTheirFolder) {
  TempDir dir;
  const std::string out = dir.file("kept");
  test::expectBadInput(
      "bench", {"applications", "--tasks", "hat", "--paper-meshes", dir.file("none"), "--out", out},
      dir.file("none") + ": --paper-meshes: ", "no such folder");
  fs::create_directories(dir.file("empty"));
  test::expectBadInput(
      "bench",
      {"applications", "--tasks", "hat", "--paper-meshes", dir.file("empty"), "--out", out},
      "--paper-meshes: ", "missing tshirt1000-tri.obj");
  test::expectBadInput("bench", {"forward", "--paper-meshes", "--out", out},
                       "--paper-meshes: ", "applications benchmark only");
  test::expectBadInput("bench", {"forward", "--resume", "--out", out},
                       "--resume: ", "applications benchmark only");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
}

// ---- the paper's meshes, in-process ----

std::string paperDir() {
  return bench::paper::defaultPaperMeshDirectory(fs::path(WEFT_ASSET_DIR).parent_path().string());
}

#define REQUIRE_PAPER_MESHES()                                                     \
  if (!bench::paper::missingPaperMeshes(paperDir()).empty())                       \
  GTEST_SKIP() << "the DiffCloth garment meshes are not in " << paperDir() << " (" \
               << bench::paper::missingPaperMeshes(paperDir())                     \
               << "); see ../shared/meshes/README.md"

// The task scene shortened to `steps` steps, its relative files made absolute, in `dir`.
std::string shortenedScene(const TempDir& dir, const std::string& task, int steps) {
  const std::string file = std::string(WEFT_ASSET_DIR) + "/scenes/" + task + ".json";
  std::ifstream in(file);
  nlohmann::json doc = nlohmann::json::parse(in);
  const std::string sceneDir = fs::path(file).parent_path().string();
  doc["time"]["steps"] = steps;
  auto& mesh = doc["cloths"][0]["mesh"];
  if (mesh.contains("file")) mesh["file"] = resolveScenePath(sceneDir, mesh["file"]);
  for (const char* term : {"trajectory", "final"})
    if (doc["task"]["loss"].contains(term))
      doc["task"]["loss"][term]["target"] =
          resolveScenePath(sceneDir, doc["task"]["loss"][term]["target"]);
  // Loss steps beyond the shortened run would be rejected by the loader.
  auto& loss = doc["task"]["loss"];
  if (loss.contains("keypoints"))
    for (auto& p : loss["keypoints"]["points"]) p["step"] = std::min(p["step"].get<int>(), steps);
  if (loss.contains("hemline")) loss["hemline"]["steps"] = {steps};
  return dir.write(task + ".json", doc.dump());
}

struct Built {
  bench::paper::PaperScene paper;
  Scene original, scene;
};

Built build(const TempDir& dir, const std::string& task, int steps) {
  const std::string file = shortenedScene(dir, task, steps);
  const bench::paper::PaperMesh* mesh = bench::paper::paperMeshFor(task);
  EXPECT_NE(mesh, nullptr);
  Built b{bench::paper::makePaperScene(file, *mesh, paperDir(), dir.file("targets")),
          loadScene(file),
          {}};
  b.scene = parseScene(b.paper.document, file, dir.path());
  return b;
}

Vec3 extent(const NodeMatrix& x) {
  return (x.colwise().maxCoeff() - x.colwise().minCoeff()).transpose();
}
Vec3 centre(const NodeMatrix& x) {
  return 0.5 * (x.colwise().maxCoeff() + x.colwise().minCoeff()).transpose();
}

// The shared checks: the paper mesh, placed on the task garment's box, every index list in
// range and near where the task's own list was, and a few steps with finite positions and the
// fixed vertices held.
void checkPaperScene(const Built& b, int paperVertices, int steps) {
  const NodeMatrix& x0 = b.original.cloths[0].mesh.vertices;
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  ASSERT_EQ(x.rows(), paperVertices);
  EXPECT_NEAR(extent(x).maxCoeff(), extent(x0).maxCoeff(), 1e-9);
  EXPECT_LT((centre(x) - centre(x0)).norm(), 1e-9);
  const double size = extent(x0).maxCoeff();
  ASSERT_FALSE(b.paper.remaps.empty());
  for (const auto& r : b.paper.remaps) {
    EXPECT_GT(r.count, 0) << r.path;
    EXPECT_LT(r.maxDistance, 0.3 * size) << r.path << ": remapped far from the task's vertices";
  }
  for (const Attachment& a : b.scene.cloths[0].attachments)
    for (int v : a.vertices) {
      EXPECT_GE(v, 0);
      EXPECT_LT(v, paperVertices);
    }
  Simulator sim(b.scene);
  Trajectory t;
  ASSERT_NO_THROW(sim.run(steps, t));
  ASSERT_EQ(t.stepCount(), steps);
  EXPECT_TRUE(t.positions.back().allFinite());
  for (const Attachment& a : b.scene.cloths[0].attachments) {
    if (a.kind != Attachment::Kind::Fixed) continue;
    for (int v : a.vertices)
      EXPECT_LT((t.positions.back().row(v) - x.row(v)).norm(), 1e-3) << "fixed vertex " << v;
  }
  // The cloth moved (gravity, wind or handles act on it).
  EXPECT_GT((t.positions.back() - x).rowwise().norm().maxCoeff(), 1e-5);
}

// The task's scene on its paper mesh, shortened to `steps`, with the shared checks made.
Built buildChecked(const TempDir& dir, const std::string& task, int steps, int paperVertices) {
  Built b = build(dir, task, steps);
  checkPaperScene(b, paperVertices, steps);
  return b;
}

TEST(PaperMeshScenes, TShirtRecordsItsTargetFromTheHiddenValues) {
  REQUIRE_PAPER_MESHES();
  TempDir dir;
  const int steps = 4;
  const Built b = buildChecked(dir, "tshirt", steps, 1426);
  // 18 hanger vertices remapped to 18 distinct shoulder vertices of the paper shirt, at its top.
  ASSERT_EQ(b.scene.cloths[0].attachments.size(), 1u);
  const auto& fixed = b.scene.cloths[0].attachments[0].vertices;
  EXPECT_GE(fixed.size(), 12u);
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  const double top = x.col(1).maxCoeff(), height = extent(x).y();
  for (int v : fixed) EXPECT_GT(x(v, 1), top - 0.3 * height) << v;
  // The target is the hidden values' motion on this mesh: simulating them reproduces it, and
  // the scene's own (starting) values do not.
  ASSERT_FALSE(b.paper.target.empty());
  const NpyArray target = readNpy(b.paper.target);
  ASSERT_EQ(target.shape, (std::vector<std::size_t>{steps + 1u, 1426u, 3u}));
  nlohmann::json hidden = b.paper.document;
  for (const auto& [path, value] :
       std::vector<std::pair<std::string, double>>{{"cloths.0.material.stretch", 300.0},
                                                   {"wind.phase", 1.0},
                                                   {"wind.frequency", 1.5},
                                                   {"wind.direction.0", 0.4},
                                                   {"wind.direction.1", 0.6},
                                                   {"wind.direction.2", 0.5}})
    ASSERT_EQ(setJsonPath(hidden, path, value), "");
  const Scene hiddenScene = parseScene(hidden, "tshirt", dir.path());
  Simulator sim(hiddenScene);
  Trajectory t;
  sim.run(steps, t);
  const std::vector<double> flat = t.flattenedPositions();
  double gap = 0.0;
  for (std::size_t i = 0; i < flat.size(); ++i)
    gap = std::max(gap, std::abs(flat[i] - target.data[i]));
  EXPECT_LT(gap, 1e-12);
  Simulator start(b.scene);
  Trajectory s;
  start.run(steps, s);
  const std::vector<double> flatStart = s.flattenedPositions();
  double differs = 0.0;
  for (std::size_t i = 0; i < flatStart.size(); ++i)
    differs = std::max(differs, std::abs(flatStart[i] - target.data[i]));
  EXPECT_GT(differs, 1e-6);
}

TEST(PaperMeshScenes, HatTargetSitsOnTheHead) {
  REQUIRE_PAPER_MESHES();
  TempDir dir;
  const Built b = buildChecked(dir, "hat", 5, 579);
  ASSERT_EQ(b.scene.cloths[0].attachments.size(), 2u);
  // The two handles hold brim vertices on opposite sides (-X and +X of the hat).
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  const double cx = centre(x).x();
  for (int v : b.scene.cloths[0].attachments[0].vertices) EXPECT_GT(x(v, 0), cx) << v;
  for (int v : b.scene.cloths[0].attachments[1].vertices) EXPECT_LT(x(v, 0), cx) << v;
  // The rebuilt target: the rest shape translated, its top centre where the task's own target
  // puts its hat's (the crown's apex 1 mm above the 0.1 m head).
  const NpyArray target = readNpy(b.paper.target);
  ASSERT_EQ(target.shape, (std::vector<std::size_t>{579u, 3u}));
  NodeMatrix t(579, 3);
  for (int i = 0; i < 579; ++i)
    for (int k = 0; k < 3; ++k) t(i, k) = target.data[3 * i + k];
  const Vec3 shift = (t.row(0) - x.row(0)).transpose();
  EXPECT_LT(((t - x).rowwise() - shift.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(t.col(1).maxCoeff(), 0.101, 1e-6);
  EXPECT_NEAR(centre(t).x(), 0.0, 1e-6);
  EXPECT_NEAR(centre(t).z(), 0.0, 1e-6);
}

// Handle paths move with their remapped vertices' rest positions: each handle still starts at
// its new vertices, and its last knot puts the handle (the mean of its vertices' targets) where
// the task's own handle ended.
TEST(PaperMeshScenes, HandlePathsEndWhereTheTasksHandlesEnd) {
  REQUIRE_PAPER_MESHES();
  for (const char* task : {"hat", "sock"}) {
    TempDir dir;
    const Built b = build(dir, task, 3);
    const auto& before = b.original.cloths[0].attachments;
    const auto& after = b.scene.cloths[0].attachments;
    ASSERT_EQ(before.size(), after.size()) << task;
    int handles = 0;
    for (std::size_t a = 0; a < after.size(); ++a) {
      if (after[a].kind != Attachment::Kind::Handle) continue;
      ++handles;
      const double end = after[a].trajectory.times.back();
      const auto meanTarget = [](const Attachment& at, const NodeMatrix& rest, double t) {
        Vec3 sum = Vec3::Zero();
        for (int v : at.vertices) sum += at.trajectory.target(rest.row(v).transpose(), t);
        return Vec3(sum / static_cast<double>(at.vertices.size()));
      };
      const NodeMatrix& x0 = b.original.cloths[0].mesh.vertices;
      const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
      EXPECT_LT((meanTarget(after[a], x, end) - meanTarget(before[a], x0, end)).norm(), 1e-9)
          << task << " attachment " << a;
      for (int v : after[a].vertices)
        EXPECT_LT(
            (after[a].trajectory.target(x.row(v).transpose(), 0.0) - x.row(v).transpose()).norm(),
            1e-12)
            << task << " attachment " << a << " starts at its vertex " << v;
    }
    EXPECT_EQ(handles, std::string(task) == "hat" ? 2 : 4);
    EXPECT_EQ(b.paper.handleShifts.size(), static_cast<std::size_t>(handles));
  }
}

TEST(PaperMeshScenes, SockKeepsItsKeypointsAndHoldsTheCuff) {
  REQUIRE_PAPER_MESHES();
  TempDir dir;
  const Built b = buildChecked(dir, "sock", 3, 1055);
  ASSERT_EQ(b.scene.cloths[0].attachments.size(), 4u);
  // Keypoint lists keep their length (they pair with positions).
  const auto& points = b.scene.task->loss["keypoints"]["points"];
  EXPECT_EQ(points[0]["vertices"].size(), 4u);
  EXPECT_EQ(points[1]["vertices"].size(), 5u);
  // The cuff faces the foot (-Z): the held vertices are at the sock's -Z end.
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  const double zmin = x.col(2).minCoeff(), length = extent(x).z();
  for (const Attachment& a : b.scene.cloths[0].attachments)
    for (int v : a.vertices) EXPECT_LT(x(v, 2), zmin + 0.1 * length) << v;
}

TEST(PaperMeshScenes, DressHemlineIsTheSkirtsHem) {
  REQUIRE_PAPER_MESHES();
  TempDir dir;
  const Built b = buildChecked(dir, "dress", 5, 681);
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  const double ymin = x.col(1).minCoeff(), ymax = x.col(1).maxCoeff(), h = ymax - ymin;
  const auto hem = b.scene.task->loss["hemline"]["vertices"].get<std::vector<int>>();
  EXPECT_GE(hem.size(), 16u);
  for (int v : hem) EXPECT_LT(x(v, 1), ymin + 0.25 * h) << v;
  for (int v : b.scene.cloths[0].attachments[0].vertices) EXPECT_GT(x(v, 1), ymax - 0.25 * h) << v;
}

TEST(PaperMeshScenes, FlagHangsFromItsPole) {
  REQUIRE_PAPER_MESHES();
  TempDir dir;
  const int steps = 5;
  const Built b = buildChecked(dir, "flag", steps, 540);
  // The pole side is at -X: the fixed vertices lie along the flag's left edge.
  const NodeMatrix& x = b.scene.cloths[0].mesh.vertices;
  const double xmin = x.col(0).minCoeff(), width = extent(x).x();
  for (int v : b.scene.cloths[0].attachments[0].vertices)
    EXPECT_LT(x(v, 0), xmin + 0.15 * width) << v;
  const NpyArray target = readNpy(b.paper.target);
  EXPECT_EQ(target.shape, (std::vector<std::size_t>{steps + 1u, 540u, 3u}));
  // The wind's falloff coefficients are those of the new vertices (inverse distance to the centre).
  ASSERT_TRUE(b.scene.wind && b.scene.wind->falloffCenter);
  EXPECT_EQ(b.scene.wind->coefficients.size(), 540);
}

}  // namespace
}  // namespace weft
