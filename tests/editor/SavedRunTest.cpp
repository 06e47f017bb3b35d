// The simulation cache saved beside the scene and reopened with it (SimulationCache::save,
// restore; EditorSession's Save and Open): the reopened run is the saved one, state by state.

#include <EditorDocument.h>
#include <EditorSession.h>
#include <SimulationCache.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/output/RunFolder.h>

#include <gtest/gtest.h>

#include <filesystem>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;

// A 1 m cloth falling onto a sphere: contact (branches, depth) from about step 10.
nlohmann::json clothOnSphere(int steps) {
  nlohmann::json scene = test::gridScene(1.0, 8, 0.01, steps, 300.0);
  scene["gravity"] = {0.0, -9.8, 0.0};
  scene["solver"] = {{"pd_iterations", 40}, {"pd_tolerance", 1e-6}};
  scene["obstacles"] = nlohmann::json::array(
      {{{"sphere", {{"center", {0.0, -0.3, 0.0}}, {"radius", 0.25}}}, {"friction", 0.3}}});
  return scene;
}

void simulate(SimulationCache& cache, const nlohmann::json& document) {
  EditorDocument doc(document);
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  cache.start(doc.sharedScene(), doc.scene()->time.steps);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done) << cache.error();
}

TEST(SavedRun, ReopensEqualToTheSavedRun) {
  test::TempDir dir;
  SimulationCache cache;
  simulate(cache, clothOnSphere(30));
  cache.save(dir.file("cloth.run"));
  for (const char* file : {"positions.npy", "velocities.npy", "stats.csv", "summary.json",
                           "scene.json", "rest.obj", "contact_branches.npy"})
    EXPECT_TRUE(fs::is_regular_file(dir.file("cloth.run/") + file)) << file;

  SimulationCache reopened;
  reopened.restore(loadRunFolder(dir.file("cloth.run")));
  EXPECT_TRUE(reopened.restored());
  EXPECT_FALSE(cache.restored());
  EXPECT_EQ(reopened.status(), SimulationCache::Status::Done);
  ASSERT_EQ(reopened.frameCount(), cache.frameCount());
  EXPECT_FALSE(reopened.staleFor(cache.scene()->document));
  int touching = 0;
  for (int k = 0; k < cache.frameCount(); ++k) {
    SCOPED_TRACE(k);
    const auto a = cache.frame(k), b = reopened.frame(k);
    EXPECT_EQ(b->state, k);
    // .npy holds the doubles themselves: bit-identical.
    EXPECT_EQ(a->positions, b->positions);
    EXPECT_EQ(a->velocities, b->velocities);
    EXPECT_EQ(a->branches, b->branches);
    for (std::uint8_t branch : b->branches) touching += branch != 0;
    if (k == 0) continue;
    EXPECT_EQ(a->stats.step, b->stats.step);
    EXPECT_EQ(a->stats.pdIterations, b->stats.pdIterations);
    EXPECT_EQ(a->stats.converged, b->stats.converged);
    EXPECT_EQ(a->stats.takeoff + a->stats.stick + a->stats.slip,
              b->stats.takeoff + b->stats.stick + b->stats.slip);
    // stats.csv prints 7 significant digits.
    EXPECT_NEAR(a->stats.residual, b->stats.residual, 1e-6 * a->stats.residual + 1e-300);
    EXPECT_NEAR(a->stats.depth, b->stats.depth, 1e-6 * a->stats.depth + 1e-300);
  }
  EXPECT_GT(touching, 0) << "the cloth reaches the sphere";
  const ConvergenceReport before = cache.convergence(), after = reopened.convergence();
  EXPECT_EQ(after.steps, before.steps);
  EXPECT_EQ(after.unconverged, before.unconverged);
  EXPECT_NEAR(after.maxDepth, before.maxDepth, 1e-6 * before.maxDepth);

  // Saved again (Save As elsewhere), a reopened run is copied, not rebuilt without its forces.
  reopened.save(dir.file("copy.run"));
  const RunFolder copy = loadRunFolder(dir.file("copy.run")),
                  original = loadRunFolder(dir.file("cloth.run"));
  ASSERT_EQ(copy.contacts.forces.size(), original.contacts.forces.size());
  for (std::size_t k = 0; k < copy.contacts.forces.size(); ++k)
    EXPECT_EQ(copy.contacts.forces[k], original.contacts.forces[k]);
}

// A `weft simulate` folder has no velocities.npy: they come from the positions, by the implicit
// Euler update x_{n+1} = x_n + h v_{n+1} (DiffCloth Eq. 4) that every step makes.
TEST(SavedRun, VelocitiesOfARunWithoutThemFollowFromThePositions) {
  test::TempDir dir;
  SimulationCache cache;
  simulate(cache, test::hangingClothScene(1.0, 6, 0.01, 12, 400.0));
  cache.save(dir.file("hanging.run"));
  fs::remove(dir.file("hanging.run/velocities.npy"));
  SimulationCache reopened;
  reopened.restore(loadRunFolder(dir.file("hanging.run")));
  ASSERT_EQ(reopened.frameCount(), 13);
  for (int k = 0; k < 13; ++k) {
    SCOPED_TRACE(k);
    const NodeMatrix& simulated = cache.frame(k)->velocities;
    const NodeMatrix& derived = reopened.frame(k)->velocities;
    EXPECT_LT((simulated - derived).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + simulated.norm()));
  }
}

TEST(SavedRun, TheSessionSavesTheRunBesideTheSceneAndReopensIt) {
  test::TempDir dir;
  nlohmann::json document = clothOnSphere(20);
  document["task"] = {{"loss", {{"hemline", {{"vertices", {0, 1, 2}}, {"height", -0.2}}}}}};
  const std::string scene = test::writeScene(dir.file("cloth.json"), document);
  {
    EditorSession session(dir.file("recent.json"));
    session.open(scene);
    EXPECT_FALSE(session.cache().restored());
    EXPECT_EQ(session.savedRunNote(), "") << "nothing beside the scene yet";
    session.timeline().simulate();
    session.cache().wait();
    EXPECT_EQ(session.save(), "");
    EXPECT_TRUE(fs::is_directory(dir.file("cloth.run")));
  }
  {
    EditorSession session(dir.file("recent.json"));
    session.open(scene);
    EXPECT_TRUE(session.cache().restored());
    EXPECT_EQ(session.cache().frameCount(), 21);
    EXPECT_FALSE(session.timeline().cacheStale());
    EXPECT_EQ(session.savedRunNote(), "run reopened from cloth.run");
    EXPECT_NE(session.gradients().compute().find("simulate again"), std::string::npos)
        << "no backward pass through a run without its contact records";
    // An edit saved without simulating leaves the old run beside a scene it no longer matches.
    ASSERT_EQ(
        session.document().edit(
            "stiffer", [](nlohmann::json& d) { d["cloths"][0]["material"]["stretch"] = 900.0; }),
        "");
    EXPECT_EQ(session.save(), "");
  }
  EditorSession session(dir.file("recent.json"));
  session.open(scene);
  EXPECT_FALSE(session.cache().restored());
  EXPECT_EQ(session.cache().frameCount(), 0);
  EXPECT_EQ(session.savedRunNote(),
            "cloth.run is the run of another version of the scene: not loaded");
}

}  // namespace
}  // namespace weft::editor
