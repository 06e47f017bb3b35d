// The timeline says what the solver did: a red banner (residual against tolerance) and a red tick
// per step that stopped at the iteration limit, for a run that hits its cap, and neither for a
// converged run or a stale one. Real binary, headless; what the last frame drew is read back
// through the state (solver_banner, unconverged_ticks).

#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace weft::test {
namespace {

std::string hangingScene(const TempDir& dir, int steps) {
  return writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, steps, 500.0));
}

TEST(EditorSolverState, CappedSolveShowsBannerAndATickPerUnconvergedStep) {
  TempDir dir;
  // One iteration per step against a tolerance no step reaches: every step stops at the cap.
  const ProcessResult r = runEditor(dir, {{{"open", hangingScene(dir, 8)}},
                                          {{"set", "solver.pd_iterations"}, {"value", 1}},
                                          {{"set", "solver.pd_tolerance"}, {"value", 1e-14}},
                                          {{"simulate", true}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("capped.json")}},
                                          // Editing the scene makes the run stale: no verdict.
                                          {{"set", "solver.pd_iterations"}, {"value", 200}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("stale.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json capped = readJson(dir.file("capped.json"));
  const int unconverged = capped["cache_unconverged_steps"];
  EXPECT_EQ(unconverged, 8);
  EXPECT_EQ(capped["unconverged_ticks"], unconverged);
  ASSERT_TRUE(capped["solver_banner"].is_string());
  const std::string banner = capped["solver_banner"];
  EXPECT_NE(banner.find("8 of 8 steps unconverged at 1 iterations"), std::string::npos) << banner;
  EXPECT_NE(banner.find("tolerance 1e-14"), std::string::npos) << banner;
  EXPECT_NE(banner.find("worst residual"), std::string::npos) << banner;

  const nlohmann::json stale = readJson(dir.file("stale.json"));
  EXPECT_TRUE(stale["cache_stale"].get<bool>());
  EXPECT_TRUE(stale["solver_banner"].is_null());
  EXPECT_EQ(stale["unconverged_ticks"], 0);
}

TEST(EditorSolverState, ConvergedRunShowsNoBannerAndNoTicks) {
  TempDir dir;
  const ProcessResult r = runEditor(dir, {{{"open", hangingScene(dir, 8)}},
                                          {{"simulate", true}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("converged.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json converged = readJson(dir.file("converged.json"));
  EXPECT_EQ(converged["cache_frames"], 9);
  EXPECT_EQ(converged["cache_unconverged_steps"], 0);
  EXPECT_TRUE(converged["solver_banner"].is_null());
  EXPECT_EQ(converged["unconverged_ticks"], 0);
}

}  // namespace
}  // namespace weft::test
