// `weft optimize` through the real binary: loss.csv, result.json and the loss plot of a tiny
// system identification, the falling loss, the gradient-free methods on the shipped wind system
// identification (budget in forward steps, seeds), and the exits of bad input (2).

#include <app/CliSupport.h>
#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using test::splitCommas;
using test::splitLines;
using test::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr int kSteps = 15;

// A 4 x 4 cloth in wind, 15 steps, whose target was simulated with stretch 250 (it starts at 300).
std::string writeTinyScene(const TempDir& dir, const nlohmann::json& extraTask = nullptr) {
  nlohmann::json doc = test::windClothScene(4, kSteps);
  nlohmann::json target = doc;
  target["cloths"][0]["material"]["stretch"] = 250.0;
  test::writeTargetTrajectory(target, dir.file("target.npy"));
  test::addTask(doc, "trajectory", "target.npy", {"cloths.0.material.stretch", "wind.strength"});
  if (extraTask.is_object())
    for (auto it = extraTask.begin(); it != extraTask.end(); ++it)
      doc["task"][it.key()] = it.value();
  return test::writeScene(dir.file("tiny.json"), doc);
}

// loss.csv without its wall-clock column (the only column that may differ between reruns).
std::vector<std::string> withoutWallSeconds(const std::string& csv) {
  std::vector<std::string> rows;
  for (const std::string& line : splitLines(csv)) {
    auto f = splitCommas(line);
    if (f.size() > 2) f.erase(f.begin() + 2);
    std::string row;
    for (const std::string& cell : f) row += cell + ",";
    rows.push_back(row);
  }
  return rows;
}

TEST(OptimizeCli, WritesLossCsvResultJsonAndPlot) {
  TempDir dir;
  const std::string scene = writeTinyScene(dir);
  const std::string out = dir.file("opt");
  const int budget = 20 * 2 * kSteps;
  const auto r = runWeft({"optimize", scene, "--budget", std::to_string(budget), "--out", out,
                          "--seed", "3", "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, StartsWith("optimize: "));

  const auto lines = splitLines(test::readFile(out + "/loss.csv"));
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "evaluation,steps,wall_s,loss,cloths.0.material.stretch,wind.strength");
  double first = 0, best = 1e300, wall = 0.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = splitCommas(lines[i]);
    ASSERT_EQ(f.size(), 6u) << lines[i];
    EXPECT_EQ(std::stoi(f[0]), static_cast<int>(i));
    EXPECT_EQ(std::stoll(f[1]), 2LL * kSteps * static_cast<long long>(i));  // forward + backward
    EXPECT_LE(std::stoll(f[1]), budget);
    EXPECT_GE(std::stod(f[2]), wall);  // cumulative wall-clock seconds
    wall = std::stod(f[2]);
    const double loss = std::stod(f[3]);
    if (i == 1) {
      first = loss;
      EXPECT_DOUBLE_EQ(std::stod(f[4]), 300.0);  // starts from the scene's values
      EXPECT_DOUBLE_EQ(std::stod(f[5]), 1.5);
    }
    best = std::min(best, loss);
  }
  EXPECT_LT(best, 1e-3 * first) << "the loss falls";

  const nlohmann::json result = nlohmann::json::parse(test::readFile(out + "/result.json"));
  for (const char* key :
       {"method", "seed", "initial_parameters", "initial_loss", "final_parameters", "final_loss",
        "evaluations", "steps", "gradient_norm", "stop_reason"})
    EXPECT_TRUE(result.contains(key)) << key;
  EXPECT_EQ(result["method"], "lbfgsb");
  EXPECT_EQ(result["seed"], 3);
  EXPECT_EQ(result["evaluations"].get<std::size_t>(), lines.size() - 1);
  EXPECT_EQ(result["steps"].get<long long>(), 2LL * kSteps * (lines.size() - 1));
  EXPECT_DOUBLE_EQ(result["initial_loss"].get<double>(), first);
  EXPECT_DOUBLE_EQ(result["final_loss"].get<double>(), best);
  EXPECT_DOUBLE_EQ(result["initial_parameters"]["cloths.0.material.stretch"].get<double>(), 300.0);
  EXPECT_NEAR(result["final_parameters"]["cloths.0.material.stretch"].get<double>(), 250.0, 5.0);
  EXPECT_NEAR(result["final_parameters"]["wind.strength"].get<double>(), 1.5, 0.03);
  if (result["plot"].is_string()) {
    EXPECT_TRUE(std::filesystem::exists(out + "/loss.png"));
  }
}

// The final parameters are checked as a scene is at load: handles driven into an obstacle are
// warned about and listed in result.json (none for the tiny scene, which has no handle).
TEST(OptimizeCli, FinalHandlesEnteringAnObstacleAreReported) {
  TempDir dir;
  const std::string clean = writeTinyScene(dir);
  const auto r = runWeft({"optimize", clean, "--max-evaluations", "1", "--out", dir.file("clean"),
                          "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const nlohmann::json none = nlohmann::json::parse(test::readFile(dir.file("clean/result.json")));
  EXPECT_EQ(none["final_handles_entering_obstacles"], nlohmann::json::array());

  // A handle on the bottom-left corner whose keyframes end 5 cm inside a sphere below it: one
  // evaluation, so the final parameters are the scene's own.
  nlohmann::json doc = nlohmann::json::parse(test::readFile(clean));
  const int corner = 4 * 5;  // the 4 x 4 grid's first vertex of its last row
  const Vec3 p = test::parse(doc, "tiny").cloths[0].mesh.vertices.row(corner).transpose();
  doc["obstacles"] = {
      {{"sphere", {{"center", {p.x(), p.y() - 0.3, p.z()}}, {"radius", 0.2}}}, {"friction", 0.0}}};
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {corner}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}},
           {{"time", kSteps * doc["time"]["dt"].get<double>()},
            {"offset", {0.0, -0.15, 0.0}}}}}}}});
  const std::string inside = test::writeScene(dir.file("inside.json"), doc);
  const auto h = runWeft({"optimize", inside, "--max-evaluations", "1", "--out", dir.file("inside"),
                          "--quiet", "--threads", "1"});
  ASSERT_EQ(h.exitCode, 0) << describe(h);
  EXPECT_THAT(h.err, HasSubstr("warning: the final parameters: "));
  const nlohmann::json result =
      nlohmann::json::parse(test::readFile(dir.file("inside/result.json")));
  ASSERT_EQ(result["final_handles_entering_obstacles"].size(), 1u) << result.dump(2);
  const std::string message = result["final_handles_entering_obstacles"][0];
  EXPECT_THAT(message, HasSubstr("attachments.1: the handle's targets enter obstacles.0 (sphere)"));
  EXPECT_THAT(message, HasSubstr("up to 50.0 mm deep"));
}

TEST(OptimizeCli, AdamLowersTheLossAndIsReproducible) {
  TempDir dir;
  const std::string scene = writeTinyScene(dir);
  std::vector<std::string> csv[2];
  for (int k = 0; k < 2; ++k) {
    const std::string out = dir.file("adam" + std::to_string(k));
    const auto r = runWeft({"optimize", scene, "--method", "adam", "--seed", "5",
                            "--max-evaluations", "15", "--out", out, "--quiet", "--threads", "1"});
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    csv[k] = withoutWallSeconds(test::readFile(out + "/loss.csv"));
    const nlohmann::json result = nlohmann::json::parse(test::readFile(out + "/result.json"));
    EXPECT_EQ(result["method"], "adam");
    EXPECT_EQ(result["evaluations"], 15);
    EXPECT_EQ(result["stop_reason"], "max evaluations");
    EXPECT_LT(result["final_loss"].get<double>(), 0.5 * result["initial_loss"].get<double>());
  }
  EXPECT_EQ(csv[0], csv[1]);
}

struct BadOptimize {
  const char* name;
  std::vector<std::string> args;
  const char* where;
  const char* phrase;
};

// --first-step reaches L-BFGS-B: its first trial point lies that far from the start in optimiser
// coordinates (log stretch, wind strength over its starting 1.5), and result.json records it.
TEST(OptimizeCli, FirstStepIsTheFirstTrialLengthInOptimiserCoordinates) {
  TempDir dir;
  const std::string scene = writeTinyScene(dir);
  const std::string out = dir.file("opt");
  const auto r = runWeft({"optimize", scene, "--max-evaluations", "2", "--first-step", "0.02",
                          "--out", out, "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = splitLines(test::readFile(out + "/loss.csv"));
  ASSERT_EQ(lines.size(), 3u);
  const auto a = splitCommas(lines[1]), b = splitCommas(lines[2]);
  const double dz0 = std::log(std::stod(b[4]) / std::stod(a[4]));
  const double dz1 = (std::stod(b[5]) - std::stod(a[5])) / 1.5;
  EXPECT_NEAR(std::hypot(dz0, dz1), 0.02, 1e-12);
  const nlohmann::json result = nlohmann::json::parse(test::readFile(out + "/result.json"));
  EXPECT_EQ(result["lbfgsb"]["first_step"].get<double>(), 0.02);
  EXPECT_EQ(result["lbfgsb"]["min_curvature_step"].get<double>(), 0.0);
}

// Every gradient's error estimate reaches result.json; with --smoothing an evaluation costs 2K
// gradient evaluations, the losses are smoothed ones, and the task loss at the result is
// reported beside them.
TEST(OptimizeCli, ReportsGradientErrorsAndSmoothing) {
  TempDir dir;
  const std::string scene = writeTinyScene(dir);
  const std::string plainOut = dir.file("plain"), smoothOut = dir.file("smooth");
  auto r = runWeft({"optimize", scene, "--max-evaluations", "4", "--out", plainOut, "--quiet",
                    "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  nlohmann::json result = nlohmann::json::parse(test::readFile(plainOut + "/result.json"));
  EXPECT_TRUE(result["smoothing"].is_null());
  EXPECT_LT(result["gradient_error_estimate"].get<double>(), 1e-3);
  EXPECT_GT(result["gradient_error_estimate"].get<double>(), 0.0)
      << "the optimiser's gradient carries the objective's estimate";
  EXPECT_EQ(result["backward"]["accuracy"], 1e-3);
  EXPECT_GE(result["backward"]["passes"].get<int>(), 2 * 4) << "two passes per gradient";
  EXPECT_EQ(result["backward"]["gradients_missing_accuracy"], 0);
  EXPECT_LT(result["backward"]["largest_error_estimate"].get<double>(), 1e-3);

  r = runWeft({"optimize", scene, "--max-evaluations", "3", "--smoothing", "0.05",
               "--smoothing-pairs", "2", "--out", smoothOut, "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("smoothed, sigma 0.05, 2 pairs; unsmoothed final"));
  result = nlohmann::json::parse(test::readFile(smoothOut + "/result.json"));
  ASSERT_TRUE(result["smoothing"].is_object()) << result.dump();
  EXPECT_EQ(result["smoothing"]["sigma"], 0.05);
  EXPECT_EQ(result["smoothing"]["pairs"], 2);
  EXPECT_GE(result["smoothing"]["last_gradient_variance"].get<double>(), 0.0);
  const double unsmoothed = result["smoothing"]["final_loss_unsmoothed"].get<double>();
  EXPECT_TRUE(std::isfinite(unsmoothed));
  EXPECT_NE(unsmoothed, result["final_loss"].get<double>()) << "the smoothed loss differs";
  EXPECT_EQ(result["steps_per_evaluation"], 2 * 2 * 2 * kSteps);
  EXPECT_EQ(result["steps"].get<long long>(),
            2LL * 2 * 2 * kSteps * result["evaluations"].get<int>());
}

TEST(OptimizeCli, BadInputExitsTwoAndKeepsAnExistingOutput) {
  TempDir dir;
  const std::string scene = writeTinyScene(dir);
  const std::string noTask = test::dataFile("scenes/hanging_wind.json");
  const std::string out = dir.file("kept");
  std::filesystem::create_directories(out);
  dir.write("kept/loss.csv", "good\n");
  const BadOptimize cases[] = {
      {"UnknownMethod", {scene, "--method", "sgd"}, "--method: ", "must be one of"},
      {"ZeroBudget", {scene, "--budget", "0"}, "--budget: ", "positive whole number"},
      {"TooSmallBudget", {scene, "--budget", "10"}, "--budget: ", "at least one evaluation"},
      // A value-only evaluation costs the 15 forward steps: 14 do not buy one.
      {"TooSmallBudgetCmaes",
       {scene, "--method", "cmaes", "--budget", "14"},
       "--budget: ",
       "no backward"},
      {"NoTask", {noTask}, "task: ", "no task"},
      {"UnknownSet", {scene, "--set", "solver.nope.x=1"}, "--set solver.nope.x: ", "unknown path"},
      {"ZeroFirstStep", {scene, "--first-step", "0"}, "--first-step: ", "finite length > 0"},
      {"NegativeCurvatureStep",
       {scene, "--min-curvature-step", "-1"},
       "--min-curvature-step: ",
       "finite length >= 0"},
      {"FirstStepForCmaes",
       {scene, "--method", "cmaes", "--first-step", "0.1"},
       "--first-step: ",
       "L-BFGS-B setting"},
      {"NegativeSmoothing", {scene, "--smoothing", "-0.1"}, "--smoothing: ", "must be a finite"},
      {"SmoothingForCmaes",
       {scene, "--method", "cmaes", "--smoothing", "0.1"},
       "--smoothing: ",
       "gradient-based methods"},
      {"PairsWithoutSmoothing",
       {scene, "--smoothing-pairs", "3"},
       "--smoothing-pairs: ",
       "needs --smoothing"},
      {"ZeroPairs",
       {scene, "--smoothing", "0.1", "--smoothing-pairs", "0"},
       "--smoothing-pairs: ",
       ""},
  };
  for (const BadOptimize& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--out", out, "--quiet"});
    test::expectBadInput("optimize", args, c.where, c.phrase);
    EXPECT_EQ(test::readFile(out + "/loss.csv"), "good\n");
  }
}

TEST(OptimizeCli, TaskBoundsAreValidatedAndHonoured) {
  TempDir dir;
  {
    // Bounds for a path that is not a task parameter: a loader error at task.bounds.
    nlohmann::json doc = test::windClothScene(4, kSteps);
    test::addTask(doc, "trajectory", "target.npy", {"cloths.0.material.stretch"});
    doc["task"]["bounds"] = {{"cloths.0.material.bend", {0.0, 1.0}}};
    const auto r = runWeft({"optimize", test::writeScene(dir.file("stray.json"), doc), "--quiet"});
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("task.bounds.cloths.0.material.bend: "));
    EXPECT_THAT(r.err, HasSubstr("not one of task.parameters"));
  }
  {
    const std::string scene =
        writeTinyScene(dir, {{"bounds", {{"cloths.0.material.stretch", {100.0, 200.0}}}}});
    const auto r = runWeft({"optimize", scene, "--quiet"});
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("task.bounds.cloths.0.material.stretch: "));
    EXPECT_THAT(r.err, HasSubstr("outside its bounds"));
  }
  {
    // The generating stretch (250) lies below the box [280, 400]: the optimum lands on 280.
    const std::string scene =
        writeTinyScene(dir, {{"bounds", {{"cloths.0.material.stretch", {280.0, 400.0}}}}});
    const std::string out = dir.file("bounded");
    const auto r = runWeft(
        {"optimize", scene, "--max-evaluations", "25", "--out", out, "--quiet", "--threads", "1"});
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    const nlohmann::json result = nlohmann::json::parse(test::readFile(out + "/result.json"));
    EXPECT_NEAR(result["final_parameters"]["cloths.0.material.stretch"].get<double>(), 280.0, 1e-6);
    const auto lines = splitLines(test::readFile(out + "/loss.csv"));
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const double s = std::stod(splitCommas(lines[i])[4]);
      EXPECT_GE(s, 280.0 - 1e-9);
      EXPECT_LE(s, 400.0 + 1e-9);
    }
  }
}

TEST(OptimizeCli, GradientFreeMethodsRunTheWindSystemIdentificationWithinBudget) {
  // wind_sysid has 30 steps: a value-only evaluation costs 30 simulated steps, so 10 fit in 310.
  const std::string scene = std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json";
  const long long budget = 310;
  TempDir dir;
  for (const std::string method : {"cmaes", "es1p1"}) {
    SCOPED_TRACE(method);
    std::vector<std::string> runs[3];
    const char* seeds[3] = {"4", "4", "5"};
    for (int k = 0; k < 3; ++k) {
      const std::string out = dir.file(method + std::to_string(k));
      const auto r = runWeft({"optimize", scene, "--method", method, "--seed", seeds[k], "--budget",
                              std::to_string(budget), "--out", out, "--quiet", "--threads", "1"});
      ASSERT_EQ(r.exitCode, 0) << describe(r);
      const std::string csv = test::readFile(out + "/loss.csv");
      runs[k] = withoutWallSeconds(csv);
      const auto lines = splitLines(csv);
      ASSERT_EQ(lines.size(), 11u);
      EXPECT_EQ(lines[0], "evaluation,steps,wall_s,loss,cloths.0.material.stretch,wind.strength");
      double first = 0.0, best = 1e300;
      for (std::size_t i = 1; i < lines.size(); ++i) {
        const auto f = splitCommas(lines[i]);
        ASSERT_EQ(f.size(), 6u) << lines[i];
        EXPECT_EQ(std::stoll(f[1]), 30LL * static_cast<long long>(i));  // forward steps only
        EXPECT_LE(std::stoll(f[1]), budget);
        if (i == 1) first = std::stod(f[3]);
        best = std::min(best, std::stod(f[3]));
      }
      EXPECT_LT(best, first) << "the loss falls";
      const nlohmann::json result = nlohmann::json::parse(test::readFile(out + "/result.json"));
      EXPECT_EQ(result["method"], method);
      EXPECT_EQ(result["stop_reason"], "budget");
      EXPECT_EQ(result["steps"], 300);
      EXPECT_EQ(result["steps_per_evaluation"], 30);
      EXPECT_EQ(result["uses_gradient"], false);
      EXPECT_TRUE(result["gradient"].is_null());
      EXPECT_TRUE(result["gradient_norm"].is_null());
      EXPECT_DOUBLE_EQ(result["final_loss"].get<double>(), best);
      if (result["plot"].is_string()) {
        EXPECT_TRUE(std::filesystem::exists(out + "/loss.png"));
      }
    }
    EXPECT_EQ(runs[0], runs[1]) << "the same seed gives the same log";
    EXPECT_NE(runs[0], runs[2]) << "another seed samples other points";
  }
}

}  // namespace
}  // namespace weft
