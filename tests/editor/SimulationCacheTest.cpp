// The simulation worker: frames appear off the calling thread, a run can be cancelled, a
// failure is reported, and the cache knows when the document has moved on. Plus playback.

#include <EditorDocument.h>
#include <SimulationCache.h>

#include "support/SceneBuilder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace weft::editor {
namespace {

std::shared_ptr<const Scene> hanging(int quads, int steps) {
  EditorDocument doc(test::hangingClothScene(1.0, quads, 0.01, steps, 200.0));
  EXPECT_TRUE(doc.valid()) << doc.validationError();
  return doc.sharedScene();
}

TEST(SimulationCache, RunFillsOneFramePerState) {
  SimulationCache cache;
  EXPECT_EQ(cache.status(), SimulationCache::Status::Empty);
  auto scene = hanging(4, 6);
  cache.start(scene, 6);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done) << cache.error();
  EXPECT_EQ(cache.frameCount(), 7);
  EXPECT_EQ(cache.requestedFrames(), 7);
  EXPECT_DOUBLE_EQ(cache.progress(), 1.0);
  const auto first = cache.frame(0), last = cache.frame(6);
  ASSERT_TRUE(first && last);
  EXPECT_EQ(first->state, 0);
  EXPECT_EQ(last->state, 6);
  EXPECT_EQ(last->positions.rows(), 25);
  // The free bottom edge falls; the pinned corner stays.
  EXPECT_LT(last->positions(24, 1), first->positions(24, 1));
  EXPECT_NEAR(last->positions(0, 1), first->positions(0, 1), 1e-3);
  EXPECT_TRUE(last->branches.empty()) << "no contact in this scene";
  EXPECT_EQ(cache.frame(7), nullptr);
}

// The cache keeps the run's convergence report as its frames arrive: the timeline and the
// script state show it, so a capped solve is never shown as a result without saying so.
TEST(SimulationCache, CountsTheStepsThatStoppedAtTheIterationLimit) {
  nlohmann::json capped = test::hangingClothScene(1.0, 4, 0.01, 5, 200.0);
  capped["solver"] = {{"method", "pd"}, {"pd_iterations", 2}, {"pd_tolerance", 1e-10}};
  EditorDocument doc(capped);
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  SimulationCache cache;
  cache.start(doc.sharedScene(), 5);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done) << cache.error();
  ConvergenceReport report = cache.convergence();
  EXPECT_EQ(report.steps, 5);
  EXPECT_EQ(report.unconverged, 5);
  EXPECT_GT(report.worstResidual, 1e-10);
  int framesUnconverged = 0;
  for (int k = 1; k <= 5; ++k) framesUnconverged += !cache.frame(k)->stats.converged;
  EXPECT_EQ(framesUnconverged, 5);

  cache.start(hanging(4, 5), 5);  // a new run starts a new report
  cache.wait();
  report = cache.convergence();
  EXPECT_EQ(report.steps, 5);
  EXPECT_EQ(report.unconverged, 0);
}

TEST(SimulationCache, CancelStopsEarlyAndKeepsTheFramesSoFar) {
  SimulationCache cache;
  cache.start(hanging(24, 100000), 100000);
  // Wait until the worker is under way, then cancel.
  for (int i = 0; i < 2000 && cache.frameCount() < 3; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto started = std::chrono::steady_clock::now();
  cache.cancel();
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
  EXPECT_EQ(cache.status(), SimulationCache::Status::Cancelled);
  EXPECT_GE(cache.frameCount(), 3);
  EXPECT_LT(cache.frameCount(), 100001);
  EXPECT_LT(cache.progress(), 1.0);
  cache.clear();
  EXPECT_EQ(cache.frameCount(), 0);
  EXPECT_EQ(cache.status(), SimulationCache::Status::Empty);
}

TEST(SimulationCache, RestartReplacesARunningSimulation) {
  SimulationCache cache;
  cache.start(hanging(24, 100000), 100000);
  cache.start(hanging(4, 3), 3);
  cache.wait();
  EXPECT_EQ(cache.status(), SimulationCache::Status::Done);
  EXPECT_EQ(cache.frameCount(), 4);
}

TEST(SimulationCache, StaleOnceTheDocumentChanges) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 3, 200.0));
  SimulationCache cache;
  EXPECT_FALSE(cache.staleFor(doc.document())) << "an empty cache is not stale";
  cache.start(doc.sharedScene(), 3);
  cache.wait();
  EXPECT_FALSE(cache.staleFor(doc.document()));
  doc.setValue("cloths.0.material.stretch", 300.0);
  EXPECT_TRUE(cache.staleFor(doc.document()));
  doc.undo();
  EXPECT_FALSE(cache.staleFor(doc.document())) << "undo returns to the simulated document";
}

TEST(SimulationCache, ExtremeInputEndsWithAStatusNeverAnException) {
  // An absurd time step on stiff cloth under strong wind: whatever the solver does, the
  // worker must end with a status, never take the editor down.
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 1.0, 20, 1e12);
  doc["wind"] = {{"direction", {1.0, 0, 0}}, {"strength", 1e6}, {"frequency", 1.0}, {"phase", 0.0}};
  doc["solver"] = {{"pd_iterations", 20}, {"pd_tolerance", 1e-4}};
  EditorDocument d(doc);
  ASSERT_TRUE(d.valid()) << "validation: " << d.validationError();
  SimulationCache cache;
  cache.start(d.sharedScene(), 5);
  cache.wait();
  const auto status = cache.status();
  EXPECT_TRUE(status == SimulationCache::Status::Done || status == SimulationCache::Status::Failed);
  if (status == SimulationCache::Status::Failed) {
    EXPECT_FALSE(cache.error().empty());
  }
}

TEST(Playback, ScrubStepAndClamp) {
  Playback p;
  p.scrub(5, 10);
  EXPECT_EQ(p.frame(), 5);
  p.scrub(50, 10);
  EXPECT_EQ(p.frame(), 9);
  p.scrub(-3, 10);
  EXPECT_EQ(p.frame(), 0);
  p.play();
  p.step(1, 10);
  EXPECT_EQ(p.frame(), 1);
  EXPECT_FALSE(p.playing()) << "stepping pauses";
  p.step(-5, 10);
  EXPECT_EQ(p.frame(), 0);
  p.scrub(3, 0);
  EXPECT_EQ(p.frame(), 0);
}

TEST(Playback, PlaysAtTheSceneRateAndStopsAtTheEnd) {
  Playback p;
  p.play();
  p.advance(0.035, 0.01, 100, false);  // 3.5 steps of wall-clock time
  EXPECT_EQ(p.frame(), 3);
  p.advance(0.005, 0.01, 100, false);  // the half step carried over completes a fourth
  EXPECT_EQ(p.frame(), 4);
  p.setSpeed(2.0);
  p.advance(0.01, 0.01, 100, false);
  EXPECT_EQ(p.frame(), 6);
  p.advance(10.0, 0.01, 100, true);  // more frames are coming: keeps playing at the end
  EXPECT_EQ(p.frame(), 99);
  EXPECT_TRUE(p.playing());
  p.advance(10.0, 0.01, 100, false);
  EXPECT_FALSE(p.playing());
  p.pause();
  p.advance(1.0, 0.01, 200, false);
  EXPECT_EQ(p.frame(), 99);
}

TEST(Playback, LoopWrapsToTheFirstFrameInsteadOfStopping) {
  Playback p;
  p.setLoop(true);
  p.scrub(8, 10);
  p.play();
  p.advance(0.035, 0.01, 10, false);  // 8 + 3 = 11: past the last frame (9), on from 0
  EXPECT_EQ(p.frame(), 1);
  EXPECT_TRUE(p.playing());
  p.advance(0.25, 0.01, 10, false);  // 1 + 25 = 26: twice round
  EXPECT_EQ(p.frame(), 6);
  p.scrub(8, 10);
  p.advance(0.05, 0.01, 10, true);  // frames still coming: waits at the last one
  EXPECT_EQ(p.frame(), 9);
  EXPECT_TRUE(p.playing());
  p.setLoop(false);
  p.advance(0.05, 0.01, 10, false);
  EXPECT_EQ(p.frame(), 9);
  EXPECT_FALSE(p.playing()) << "without loop it stops at the end";
}

}  // namespace
}  // namespace weft::editor
