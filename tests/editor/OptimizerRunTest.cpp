// The optimiser off the UI thread: it starts paused, runs exactly the evaluations it is allowed,
// lowers the loss of the system identification scene, can be resumed and cancelled, and refuses
// what it cannot run with a message instead of starting.

#include <OptimizerRun.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace weft::editor {
namespace {

Scene windSysid() {
  return loadScene(std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json");
}

// Waits (polling) until the run is paused or over. The bound only keeps a broken run from
// hanging the suite; nothing is asserted about time.
void settle(const OptimizerRun& run) {
  for (int i = 0; i < 60000; ++i) {
    const OptimizerRun::Status s = run.status();
    if (s != OptimizerRun::Status::Running) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  FAIL() << "the optimiser neither paused nor finished";
}

TEST(OptimizerRun, MethodsComeFromTheEngine) {
  const std::vector<std::string> methods = OptimizerRun::methods();
  EXPECT_NE(std::find(methods.begin(), methods.end(), "lbfgsb"), methods.end());
  EXPECT_NE(std::find(methods.begin(), methods.end(), "adam"), methods.end());
}

TEST(OptimizerRun, StepsOneEvaluationAtATimeAndLowersTheLoss) {
  OptimizerRun run;
  OptimizerRun::Setup setup;
  setup.parameters = {"cloths.0.material.stretch", "wind.strength"};
  setup.settings.maxEvaluations = 40;
  ASSERT_EQ(run.start(windSysid(), setup, true), "");
  settle(run);
  EXPECT_EQ(run.status(), OptimizerRun::Status::Paused);
  EXPECT_EQ(run.evaluations(), 0) << "a paused start evaluates nothing";
  EXPECT_EQ(run.initialValues(), (std::vector<double>{400.0, 1.5}));

  for (int expected = 1; expected <= 4; ++expected) {
    run.step(1);
    // The gate lets one evaluation through, then holds the next one.
    for (int i = 0; i < 60000 && run.evaluations() < expected; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    settle(run);
    EXPECT_EQ(run.evaluations(), expected);
    EXPECT_EQ(run.status(), OptimizerRun::Status::Paused);
  }
  const std::vector<OptimizerRun::Sample> samples = run.samples();
  ASSERT_EQ(samples.size(), 4u);
  // The first evaluation is at the start (through the optimiser's coordinates and back).
  EXPECT_NEAR(samples[0].values[0], 400.0, 1e-9);
  EXPECT_NEAR(samples[0].values[1], 1.5, 1e-12);
  EXPECT_LT(run.best()->loss, samples[0].loss) << "the loss falls";

  // Resumed, it runs to its own stop and recovers the generating values (250 N/m, 2.0 N/m^2).
  run.resume();
  run.wait();
  EXPECT_EQ(run.status(), OptimizerRun::Status::Finished) << run.error();
  EXPECT_FALSE(run.stopReason().empty());
  EXPECT_LT(run.best()->loss, 1e-6 * samples[0].loss);
  EXPECT_NEAR(run.best()->values[0], 250.0, 1.0);
  EXPECT_NEAR(run.best()->values[1], 2.0, 0.01);
  EXPECT_EQ(run.unconvergedForwardSteps(), 0) << "the scene's steps converge";
  // Every gradient carries its error estimate, within the scene's accuracy (the panel shows it).
  EXPECT_EQ(run.gradientsMissingAccuracy(), 0);
  EXPECT_LT(run.largestGradientError(), 1e-3);
  for (const OptimizerRun::Sample& s : run.samples()) {
    EXPECT_TRUE(s.hasGradient) << "L-BFGS-B evaluates gradients";
    EXPECT_LE(s.gradientError, run.largestGradientError());
    EXPECT_GT(s.gradientError, 0.0) << "each sample carries its gradient's estimate";
  }
}

TEST(OptimizerRun, CountsTheUnconvergedForwardStepsItDifferentiates) {
  // One solver iteration per step cannot reach wind_sysid's 1e-6 tolerance: every forward step
  // of the evaluation stops at the limit, and the run says so (the panel shows the warning).
  Scene scene = windSysid();
  scene.solver.pdIterations = 1;
  OptimizerRun run;
  OptimizerRun::Setup setup;
  setup.parameters = {"wind.strength"};
  ASSERT_EQ(run.start(scene, setup, true), "");
  run.step(1);
  for (int i = 0; i < 60000 && run.evaluations() < 1; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  settle(run);
  ASSERT_EQ(run.evaluations(), 1);
  EXPECT_EQ(run.unconvergedForwardSteps(), scene.time.steps);
  run.cancel();
}

TEST(OptimizerRun, CancelStopsAPausedRunAndKeepsItsSamples) {
  OptimizerRun run;
  OptimizerRun::Setup setup;
  setup.method = "adam";
  setup.parameters = {"wind.strength"};
  ASSERT_EQ(run.start(windSysid(), setup, true), "");
  run.step(2);
  for (int i = 0; i < 60000 && run.evaluations() < 2; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  settle(run);
  run.cancel();
  EXPECT_EQ(run.status(), OptimizerRun::Status::Cancelled);
  EXPECT_EQ(run.evaluations(), 2);
  EXPECT_EQ(run.parameters(), std::vector<std::string>{"wind.strength"});
}

// Cancel stops inside the evaluation under way, between two of its steps, instead of waiting
// for it to end: a 400-step evaluation is cancelled a few steps into its forward pass and no
// evaluation completes. The progress it reported named that evaluation, phase and step.
TEST(OptimizerRun, CancelStopsWithinTheEvaluationUnderWay) {
  test::TempDir dir;
  nlohmann::json doc = test::hangingClothScene(1.0, 12, 0.01, 400, 500.0);
  doc["task"] = {
      {"loss",
       {{"keypoints",
         {{"points", {{{"step", 400}, {"vertices", {0}}, {"positions", {{0.0, 0.0, 0.0}}}}}}}}}},
      {"parameters", {"cloths.0.material.stretch"}}};
  const Scene scene = loadScene(test::writeScene(dir.file("long.json"), doc));
  OptimizerRun run;
  OptimizerRun::Setup setup;
  setup.parameters = {"cloths.0.material.stretch"};
  ASSERT_EQ(run.start(scene, setup, false), "");
  OptimizerRun::Progress seen;
  for (int i = 0; i < 60000; ++i) {
    seen = run.progress();
    if (seen.active && seen.done >= 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(seen.active);
  EXPECT_EQ(seen.evaluation, 1);
  EXPECT_EQ(seen.phase, PassPhase::Forward);
  EXPECT_EQ(seen.total, 400);
  run.cancel();
  EXPECT_EQ(run.status(), OptimizerRun::Status::Cancelled);
  EXPECT_EQ(run.evaluations(), 0) << "stopped inside evaluation 1, not after it";
  EXPECT_FALSE(run.progress().active);
  EXPECT_EQ(run.stopReason(), "cancelled");
}

TEST(OptimizerRun, RefusesWhatItCannotRun) {
  OptimizerRun run;
  OptimizerRun::Setup setup;
  setup.parameters = {"wind.strength"};
  setup.method = "simplex";
  EXPECT_NE(run.start(windSysid(), setup, false).find("unknown optimisation method 'simplex'"),
            std::string::npos);
  setup.method = "lbfgsb";
  setup.parameters.clear();
  EXPECT_NE(run.start(windSysid(), setup, false).find("choose at least one parameter"),
            std::string::npos);
  setup.parameters = {"cloths.0.material.colour"};
  EXPECT_FALSE(run.start(windSysid(), setup, false).empty());
  // No task: nothing to minimise.
  const Scene plain = test::parse(test::hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  setup.parameters = {"cloths.0.material.stretch"};
  EXPECT_NE(run.start(plain, setup, false).find("no task"), std::string::npos);
  EXPECT_EQ(run.status(), OptimizerRun::Status::Idle);
}

}  // namespace
}  // namespace weft::editor
