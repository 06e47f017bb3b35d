// `weft bench applications` through the real binary, on the smallest Flying Napkin with a tiny
// budget: every method and seed logged within the budget, the methods of one seed starting from
// the same point and the seeds from different ones, the Markdown tables, and bad input (exit 2).

#include <app/CliSupport.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using test::splitCommas;
using test::splitLines;
using test::TempDir;

TEST(ApplicationsBenchCli, RunsEveryMethodAndSeedWithinTheBudget) {
  TempDir dir;
  const std::string out = dir.file("bench");
  const long long budget = 450;  // napkin_4x4: 50 steps, so 4 gradient evaluations or 9 values
  const auto r = runWeft({"bench", "applications", "--tasks", "napkin_4x4", "--seeds", "2",
                          "--budget", std::to_string(budget), "--out", out, "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = splitLines(test::readFile(out + "/applications.csv"));
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "task,method,seed,evaluation,steps,wall_s,loss");
  std::map<std::string, int> evaluations;   // method/seed -> rows
  std::map<std::string, double> firstLoss;  // method/seed -> loss at evaluation 1
  std::map<std::string, double> lastWall;   // method/seed -> wall s at its last evaluation
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = splitCommas(lines[i]);
    ASSERT_EQ(f.size(), 7u) << lines[i];
    EXPECT_EQ(f[0], "napkin_4x4");
    const std::string run = f[1] + "/" + f[2];
    EXPECT_EQ(std::stoi(f[3]), ++evaluations[run]) << lines[i];
    const long long steps = std::stoll(f[4]);
    EXPECT_LE(steps, budget);
    EXPECT_EQ(steps, (f[1] == "lbfgsb" ? 100LL : 50LL) * std::stoi(f[3])) << lines[i];
    if (f[3] == "1") firstLoss[run] = std::stod(f[6]);
    lastWall[run] = std::stod(f[5]);
  }
  for (const char* method : {"lbfgsb", "cmaes", "es1p1"})
    for (const char* seed : {"1", "2"})
      EXPECT_TRUE(evaluations.count(std::string(method) + "/" + seed)) << method << seed;
  EXPECT_EQ(evaluations["lbfgsb/1"], 4);
  EXPECT_EQ(evaluations["cmaes/1"], 9);
  EXPECT_EQ(evaluations["es1p1/2"], 9);
  // The start is the seed's, the same for every method.
  EXPECT_EQ(firstLoss["lbfgsb/1"], firstLoss["cmaes/1"]);
  EXPECT_EQ(firstLoss["lbfgsb/1"], firstLoss["es1p1/1"]);
  EXPECT_EQ(firstLoss["lbfgsb/2"], firstLoss["es1p1/2"]);
  EXPECT_NE(firstLoss["lbfgsb/1"], firstLoss["lbfgsb/2"]);

  const std::string md = test::readFile(out + "/applications.md");
  for (const char* heading :
       {"Loss reached (DiffCloth Table 2)", "Steps to converge and to reach a threshold",
        "Every seed (DiffCloth Tables 5-6)", "| napkin_4x4 | 48 | 2 | 450 |"})
    EXPECT_NE(md.find(heading), std::string::npos) << heading;
  EXPECT_TRUE(std::filesystem::exists(out + "/loss_napkin_4x4.png") ||
              r.err.find("gnuplot") != std::string::npos);
  // The Table 4 analogue: one timed forward and backward pass of the napkin's 50 steps.
  EXPECT_NE(md.find("Seconds per pass (DiffCloth Table 4)"), std::string::npos);
  EXPECT_EQ(md.find("Beside the paper"), std::string::npos) << "the paper has no napkin row";
  const auto passes = splitLines(test::readFile(out + "/passes.csv"));
  ASSERT_EQ(passes.size(), 2u);
  const auto p = splitCommas(passes[1]);
  ASSERT_EQ(p.size(), 12u) << passes[1];
  EXPECT_EQ(p[0], "napkin_4x4");
  EXPECT_EQ(p[1], "48");  // 16 nodes
  EXPECT_EQ(p[2], "50");
  EXPECT_GT(std::stod(p[4]), 0.0);  // forward s
  EXPECT_GT(std::stod(p[5]), 0.0);  // backward s
  EXPECT_EQ(p[7], "100") << "GMRES converges on every step of the free napkin";
  EXPECT_EQ(p[8], "0");              // unconverged forward steps
  EXPECT_GE(std::stod(p[9]), 1.0);   // adjoint growth
  EXPECT_GT(std::stod(p[10]), 0.0);  // mean L-BFGS-B evaluation of the runs
  // The six runs' wall seconds together (each run's is its last evaluation's), in the table and
  // in the setup line: what the comparison costs, whatever ran beside it.
  double runSeconds = 0.0;
  for (const auto& [run, wall] : lastWall) runSeconds += wall;
  EXPECT_NEAR(std::stod(p[11]), runSeconds, 1e-3 * runSeconds) << passes[1];
  EXPECT_NE(md.find("The runs' wall seconds add up to " + p[11] + " s"), std::string::npos);
}

// A task the paper tabulates gets its row beside DiffCloth's published figures (Tables 2-4).
TEST(ApplicationsBenchCli, PaperTasksArePrintedBesideThePublishedFigures) {
  TempDir dir;
  const std::string out = dir.file("bench");
  // flag: 100 steps, so one gradient evaluation or two values.
  const auto r = runWeft({"bench", "applications", "--tasks", "flag", "--seeds", "1", "--budget",
                          "200", "--out", out, "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const std::string md = test::readFile(out + "/applications.md");
  const auto section = md.find("## Beside the paper (DiffCloth Tables 2-4)");
  ASSERT_NE(section, std::string::npos) << md;
  const std::string beside = md.substr(section, md.find("\n## ", section + 1) - section);
  EXPECT_NE(beside.find("| flag | Weft | 8 | 1 |"), std::string::npos) << beside;
  // Table 2: 4.77 / 10.57 / 38.89 / 25.57 / 40.14; Table 3: 6800 / 17300 / 24800, 96 %;
  // Table 4: 13.7 s / 1.6 s.
  EXPECT_NE(
      beside.find("| Flag | DiffCloth | 8 | 10 | 4.77 | 10.57 | 38.89 | 25.57 | 40.14 | 6800 | "
                  "17300 | 24800 | 2.54 | 96 | 13.7 | 1.6 |"),
      std::string::npos)
      << beside;
  const auto passes = splitLines(test::readFile(out + "/passes.csv"));
  ASSERT_EQ(passes.size(), 2u);
  const auto p = splitCommas(passes[1]);
  ASSERT_EQ(p.size(), 12u) << passes[1];
  EXPECT_EQ(p[0], "flag");
  EXPECT_EQ(p[2], "100");
  EXPECT_EQ(p[7], "100") << "GMRES converges on every backward step of the flag (measured)";
  EXPECT_GT(std::stod(p[4]), 0.0);  // forward s
  EXPECT_GT(std::stod(p[5]), 0.0);  // backward s
  // The aim: with one gradient evaluation (the start) L-BFGS-B has not reached the
  // paper's 4.77 % of the initial loss, so the aim is not met on this budget.
  const auto aim = md.find("## Steps to the paper's loss (the issue's aim)");
  ASSERT_NE(aim, std::string::npos) << md;
  const std::string aimTable = md.substr(aim, md.find("\n## ", aim + 1) - aim);
  EXPECT_NE(aimTable.find("| flag | paper's L-BFGS-B 4.77 % |"), std::string::npos) << aimTable;
  EXPECT_NE(aimTable.find("| > 200 | > 200 | > 200 | - | not met: L-BFGS-B does not reach it |"),
            std::string::npos)
      << aimTable;
}

// L-BFGS-B's settings reach its runs, are named in applications.md and stored with the runs, and
// a store made with other settings is not resumed with these.
TEST(ApplicationsBenchCli, LbfgsbSettingsAreRecordedWithTheRuns) {
  TempDir dir;
  const std::string out = dir.file("bench");
  const std::vector<std::string> common = {
      "bench",    "applications", "--tasks",   "napkin_4x4", "--seeds",   "1",
      "--budget", "300",          "--methods", "lbfgsb",     "--threads", "1"};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--first-step", "0.01", "--out", out});
  const auto r = runWeft(args);
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const std::string md = test::readFile(out + "/applications.md");
  EXPECT_NE(md.find("L-BFGS-B: first trial step 0.01 (optimiser coordinates; LBFGSpp's is 1), "
                    "curvature pairs of steps shorter than 0 left out"),
            std::string::npos)
      << md;
  const nlohmann::json settings =
      nlohmann::json::parse(test::readFile(out + "/runs/settings.json"));
  EXPECT_EQ(settings["lbfgsb_first_step"].get<double>(), 0.01);
  EXPECT_TRUE(settings["lbfgsb_min_curvature_step"].is_null());
  // Resuming those runs with L-BFGS-B's defaults would mix two methods under one name.
  std::vector<std::string> resume = common;
  resume.insert(resume.end(), {"--resume", "--seeds", "2", "--out", out});
  test::expectBadInput("bench", {resume.begin() + 1, resume.end()},
                       "lbfgsb_first_step: ", "--first-step 0.01");
}

// A finished comparison of one L-BFGS-B run of the smallest napkin: the command that made it and
// the settings stored with its runs.
struct FinishedStore {
  TempDir dir;
  std::string out = dir.file("bench");
  std::vector<std::string> args = {
      "bench", "applications", "--tasks", "napkin_4x4", "--seeds", "1",     "--budget",
      "300",   "--methods",    "lbfgsb",  "--threads",  "1",       "--out", out};
  nlohmann::json settings;
};

void makeFinishedStore(FinishedStore& store) {
  const auto r = runWeft(store.args);
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  store.settings = nlohmann::json::parse(test::readFile(store.out + "/runs/settings.json"));
  ASSERT_TRUE(store.settings.contains("build"));
}

// With the store's settings.json replaced by `stored`, resuming it with one more seed is refused
// as `option`: `what`, and its runs are kept.
void expectMoreSeedsRefused(FinishedStore& store, const nlohmann::json& stored,
                            const std::string& option, const std::string& what) {
  store.dir.write("bench/runs/settings.json", stored.dump(2));
  std::vector<std::string> more(store.args.begin() + 1, store.args.end());
  more.insert(more.end(), {"--resume", "--seeds", "2"});
  test::expectBadInput("bench", more, option, what);
  EXPECT_TRUE(std::filesystem::exists(store.out + "/runs/napkin_4x4_lbfgsb_1.csv"));
}

// The build that made the runs is stored with them and named in applications.md; a store made by
// a build with other engine sources is not resumed (a docs-only commit, i.e. another commit with
// the same engine, CLI and assets, is).
TEST(ApplicationsBenchCli, RunsRecordTheirBuildAndOtherEnginesDoNotResumeThem) {
  const auto version = runWeft({"--version"});
  ASSERT_EQ(version.exitCode, 0) << describe(version);
  FinishedStore store;
  ASSERT_NO_FATAL_FAILURE(makeFinishedStore(store));
  TempDir& dir = store.dir;
  const std::string& out = store.out;
  const std::vector<std::string>& args = store.args;
  const std::string settingsFile = out + "/runs/settings.json";
  const nlohmann::json& settings = store.settings;
  const nlohmann::json build = settings["build"];
  if (!build["commit"].is_string()) GTEST_SKIP() << "built without git: nothing recorded";
  const std::string commit = build["commit"].get<std::string>();
  EXPECT_EQ(commit.size(), 40u);
  for (const char* key : {"engine", "app", "assets"})
    EXPECT_EQ(build[key].get<std::string>().size(), 40u) << key;
  EXPECT_NE(version.out.find("commit " + commit.substr(0, 12)), std::string::npos) << version.out;
  const std::string md = test::readFile(out + "/applications.md");
  EXPECT_NE(md.find("Build: runs made by commit " + commit.substr(0, 12)), std::string::npos) << md;

  // Another engine made these runs: refused, the runs kept.
  nlohmann::json other = settings;
  other["build"]["engine"] = std::string(40, '0');
  expectMoreSeedsRefused(
      store, other, "settings.json: build.engine: ", "engine/ sources differ from this build's");
  std::vector<std::string> resume(args.begin() + 1, args.end());
  resume.insert(resume.end(), {"--resume", "--seeds", "2"});

  // Another commit with the same sources: resumed, and the page says which build wrote it.
  other = settings;
  other["build"]["commit"] = std::string(40, 'a');
  dir.write("bench/runs/settings.json", other.dump(2));
  resume.insert(resume.begin(), "bench");
  const auto resumed = runWeft(resume);
  ASSERT_EQ(resumed.exitCode, 0) << describe(resumed);
  const std::string md2 = test::readFile(out + "/applications.md");
  EXPECT_NE(md2.find("Build: runs made by commit aaaaaaaaaaaa"), std::string::npos) << md2;
  EXPECT_NE(md2.find("; tables written by commit " + commit.substr(0, 12)), std::string::npos)
      << md2;

  // A store from before builds were recorded: resumed, and not said to match.
  other = nlohmann::json::parse(test::readFile(settingsFile));
  other.erase("build");
  dir.write("bench/runs/settings.json", other.dump(2));
  const auto old = runWeft(resume);
  ASSERT_EQ(old.exitCode, 0) << describe(old);
  const std::string md3 = test::readFile(out + "/applications.md");
  EXPECT_NE(md3.find("Build: the stored runs carry no build record"), std::string::npos) << md3;
  EXPECT_EQ(md3.find("same engine"), std::string::npos) << md3;
}

// A build whose app/weft/ differs (a new table, a corrected report) may tabulate a store whose
// runs are all made, with the same engine and assets; it may not add runs to it.
TEST(ApplicationsBenchCli, AnotherCliTabulatesAFinishedStoreButAddsNoRuns) {
  FinishedStore store;
  ASSERT_NO_FATAL_FAILURE(makeFinishedStore(store));
  TempDir& dir = store.dir;
  const std::string& out = store.out;
  const std::vector<std::string>& args = store.args;
  nlohmann::json settings = store.settings;
  if (!settings["build"]["commit"].is_string()) GTEST_SKIP() << "built without git";
  settings["build"]["app"] = std::string(40, '0');
  expectMoreSeedsRefused(store, settings,
                         "settings.json: build.app: ", "1 run(s) are still to be made");

  std::vector<std::string> same = args;
  same.push_back("--resume");
  const auto tabulated = runWeft(same);
  ASSERT_EQ(tabulated.exitCode, 0) << describe(tabulated);
  EXPECT_NE(tabulated.out.find("0 run(s) made, 1 resumed"), std::string::npos) << tabulated.out;
  const std::string md = test::readFile(out + "/applications.md");
  EXPECT_NE(md.find("its app/weft/ differs, so it made no runs"), std::string::npos) << md;
  // Tasks without handles get no handle table.
  EXPECT_EQ(md.find("Handles at each run's best point"), std::string::npos) << md;

  // Another engine still may not even tabulate.
  settings["build"]["engine"] = std::string(40, '0');
  dir.write("bench/runs/settings.json", settings.dump(2));
  test::expectBadInput("bench", std::vector<std::string>(same.begin() + 1, same.end()),
                       "settings.json: build.engine: ", "engine/ sources differ");
}

// The table of where each run's best point puts the handles, from the committed Hat store
// (docs/runs/hat, made before builds were recorded, so any build tabulates it): every row agrees
// with the scene check `weft simulate` prints for that run's best parameter values.
TEST(ApplicationsBenchCli, HandleTableAgreesWithTheSceneCheckAtEachBestPoint) {
  const std::filesystem::path stored =
      std::filesystem::path(WEFT_ASSET_DIR).parent_path() / "docs" / "runs" / "hat";
  if (!std::filesystem::exists(stored / "settings.json")) GTEST_SKIP() << "no stored Hat runs";
  TempDir dir;
  const std::string out = dir.file("bench");
  std::filesystem::create_directories(out);
  std::filesystem::copy(stored, out + "/runs", std::filesystem::copy_options::recursive);
  const auto r = runWeft({"bench", "applications", "--tasks", "hat", "--seeds", "3", "--resume",
                          "--threads", "1", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const std::string md = test::readFile(out + "/applications.md");
  const std::size_t table = md.find("Handles at each run's best point");
  ASSERT_NE(table, std::string::npos) << md;
  int checked = 0, inside = 0;
  const char* methods[] = {"lbfgsb", "cmaes", "es1p1"};
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string prefix = "| hat | " + std::to_string(seed) + " | ";
    const std::size_t row = md.find(prefix, table);
    ASSERT_NE(row, std::string::npos) << prefix;
    const auto cells = splitCommas([&] {
      std::string line = md.substr(row + prefix.size(), md.find('\n', row) - row - prefix.size());
      for (char& c : line) c = c == '|' ? ',' : c;
      return line;
    }());
    for (int m = 0; m < 3; ++m) {
      const double depth = std::stod(cells[m]);
      // The run's best evaluation and its parameter values, as a user would find them.
      const std::string name = std::string("hat_") + methods[m] + "_" + std::to_string(seed);
      const auto runRows = splitLines(test::readFile(out + "/runs/" + name + ".csv"));
      std::string best;
      double bestLoss = 1e300;
      for (std::size_t i = 1; i < runRows.size(); ++i) {
        const auto f = splitCommas(runRows[i]);
        if (std::stod(f[6]) < bestLoss) bestLoss = std::stod(f[6]), best = f[3];
      }
      const auto parameterRows =
          splitLines(test::readFile(out + "/runs/parameters/" + name + ".csv"));
      const auto paths = splitCommas(parameterRows[0]);
      std::vector<std::string> args = {
          "simulate",    std::string(WEFT_ASSET_DIR) + "/scenes/hat.json",
          "--steps",     "1",
          "--quiet",     "--out",
          dir.file(name)};
      for (std::size_t i = 1; i < parameterRows.size(); ++i) {
        const auto f = splitCommas(parameterRows[i]);
        if (f[0] != best) continue;
        for (std::size_t k = 1; k < f.size(); ++k)
          args.insert(args.end(), {"--set", paths[k] + "=" + f[k]});
      }
      ASSERT_GT(args.size(), 7u) << name << " evaluation " << best;
      const auto sim = runWeft(args);
      ASSERT_EQ(sim.exitCode, 0) << describe(sim);
      // The warning's deepest depth ("up to D mm deep") over the scene's handles, 0 without one.
      double warned = 0.0;
      for (std::size_t at = sim.err.find("up to "); at != std::string::npos;
           at = sim.err.find("up to ", at + 1))
        warned = std::max(warned, std::stod(sim.err.substr(at + 6)));
      EXPECT_NEAR(depth, warned, 0.05 + 1e-3 * warned) << name << "\n" << sim.err;
      ++checked;
      inside += depth > 0.0;
    }
  }
  EXPECT_EQ(checked, 9);
  EXPECT_GT(inside, 0) << "the stored runs include best points with a handle in the head";
}

TEST(ApplicationsBenchCli, SeedsPerTaskMakeThatManySeedsOfThatTask) {
  TempDir dir;
  const std::string out = dir.file("bench");
  // napkin_4x4 and napkin_5x5: 50 steps each, so 200 steps is two gradient evaluations or four
  // values per run.
  const auto r = runWeft({"bench", "applications", "--tasks", "napkin_4x4,napkin_5x5", "--seeds",
                          "1,napkin_5x5=2", "--budget", "200", "--out", out, "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  std::map<std::string, std::set<std::string>> seeds;  // task -> seeds with runs
  const auto lines = splitLines(test::readFile(out + "/applications.csv"));
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = splitCommas(lines[i]);
    ASSERT_EQ(f.size(), 7u) << lines[i];
    seeds[f[0]].insert(f[2]);
  }
  EXPECT_EQ(seeds["napkin_4x4"], (std::set<std::string>{"1"}));
  EXPECT_EQ(seeds["napkin_5x5"], (std::set<std::string>{"1", "2"}));
  const std::string md = test::readFile(out + "/applications.md");
  for (const char* text : {"| napkin_4x4 | 48 | 1 | 200 |", "| napkin_5x5 | 75 | 2 | 200 |",
                           "1 seed(s) per task (1..1), napkin_5x5 2 (1..2)"})
    EXPECT_NE(md.find(text), std::string::npos) << text;
}

TEST(ApplicationsBenchCli, BadInputExitsTwo) {
  TempDir dir;
  const std::string out = dir.file("kept");
  test::expectBadInput("bench", {"applications", "--tasks", "napkin_3x3", "--out", out},
                       "--tasks: ", "unknown task");
  test::expectBadInput("bench", {"applications", "--seeds", "0", "--out", out}, "--seeds", "");
  test::expectBadInput(
      "bench", {"applications", "--tasks", "napkin_4x4", "--seeds", "2,sock=1", "--out", out},
      "--seeds: ", "not one of the tasks run");
  test::expectBadInput("bench", {"applications", "--seeds", "2,sock", "--out", out},
                       "--seeds: ", "is not task=M");
  test::expectBadInput("bench", {"applications", "--seeds", "2,sock=x", "--out", out},
                       "--seeds: ", "whole numbers 1..100");
  test::expectBadInput("bench",
                       {"applications", "--tasks", "napkin_4x4", "--budget", "60", "--out", out},
                       "--budget: ", "at least one gradient evaluation");
  test::expectBadInput("bench", {"forward", "--tasks", "napkin_4x4", "--out", out},
                       "--tasks: ", "applications benchmark only");
  test::expectBadInput("bench", {"applications", "--first-step", "0", "--out", out},
                       "--first-step: ", "finite length > 0");
  test::expectBadInput("bench", {"backward", "--min-curvature-step", "0.1", "--out", out},
                       "--min-curvature-step: ", "applications benchmark only");
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace weft
