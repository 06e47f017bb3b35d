// Final-frame targets: the task's final term and the sidecar positions change together (one
// undo step), the .npy the editor writes is what the engine's loss reads, an opened scene's
// targets come back from their file, and the live loss of a cached run is the engine's loss.

#include <EditorDocument.h>
#include <FinalTargets.h>
#include <LiveLoss.h>
#include <SimulationCache.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/diff/TaskLoss.h>
#include <weft/io/Npy.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

namespace weft::editor {
namespace {

using test::TempDir;

TEST(FinalTargets, SetAndRemoveEditTheTaskAndTheSidecarTogether) {
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 0.01, 5, 500.0);
  nlohmann::json sidecar = nlohmann::json::object();
  setFinalTargets(doc, sidecar,
                  {{12, Vec3(0.1, 0.2, 0.3)}, {3, Vec3(1, 2, 3)}, {12, Vec3(9, 9, 9)}},
                  "x-final-target.npy");
  // Sorted by vertex; of two targets for one vertex the first is kept.
  EXPECT_EQ(doc["task"]["loss"]["final"]["vertices"], nlohmann::json::array({3, 12}));
  EXPECT_EQ(doc["task"]["loss"]["final"]["target"], "x-final-target.npy");
  const std::vector<FinalTarget> read = finalTargets(sidecar);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].node, 3);
  EXPECT_EQ(read[1].position, Vec3(0.1, 0.2, 0.3));
  EXPECT_NO_THROW(test::parse(doc)) << "the task validates";

  // A weight typed in the scene survives later target edits; the file name stays the first one.
  doc["task"]["loss"]["final"]["weight"] = 4.0;
  setFinalTargets(doc, sidecar, {{5, Vec3::Zero()}}, "other.npy");
  EXPECT_EQ(doc["task"]["loss"]["final"]["weight"], 4.0);
  EXPECT_EQ(doc["task"]["loss"]["final"]["target"], "x-final-target.npy");

  // Removing the last target removes the term and the task it alone made up.
  setFinalTargets(doc, sidecar, {}, "x.npy");
  EXPECT_FALSE(doc.contains("task"));
  EXPECT_FALSE(sidecar.contains("final_targets"));
  // A task with parameters keeps its other terms.
  doc["task"] = {{"loss", {{"trajectory", {{"target", "run.npy"}}}}},
                 {"parameters", {"cloths.0.material.stretch"}}};
  setFinalTargets(doc, sidecar, {{1, Vec3::Ones()}}, "x.npy");
  setFinalTargets(doc, sidecar, {}, "x.npy");
  EXPECT_TRUE(doc["task"]["loss"].contains("trajectory"));
  EXPECT_FALSE(doc["task"]["loss"].contains("final"));
}

TEST(FinalTargets, UndoRestoresTheSidecarWithTheDocument) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  auto set = [&](std::vector<FinalTarget> t) {
    return doc.editWithSidecar("targets", [&](nlohmann::json& d, nlohmann::json& s) {
      setFinalTargets(d, s, t, "t.npy");
    });
  };
  ASSERT_EQ(set({{7, Vec3(0, 1, 0)}}), "");
  ASSERT_EQ(set({{7, Vec3(0, 2, 0)}}), "");
  EXPECT_EQ(finalTargets(doc.sidecar())[0].position.y(), 2.0);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(finalTargets(doc.sidecar())[0].position.y(), 1.0);
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(finalTargets(doc.sidecar()).empty());
  EXPECT_FALSE(doc.find("task"));
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(finalTargets(doc.sidecar())[0].position.y(), 1.0);
  // Edits with one coalescing key (a drag) are one undo step.
  for (double y : {3.0, 4.0, 5.0})
    doc.editWithSidecar(
        "drag",
        [&](nlohmann::json& d, nlohmann::json& s) {
          setFinalTargets(d, s, {{7, Vec3(0, y, 0)}}, "t.npy");
        },
        "drag 1");
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(finalTargets(doc.sidecar())[0].position.y(), 1.0);
}

TEST(FinalTargets, WrittenFileIsWhatTheEngineReadsAndComesBackOnOpen) {
  TempDir dir;
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 0.01, 5, 500.0);
  nlohmann::json sidecar = nlohmann::json::object();
  const std::vector<FinalTarget> targets = {{20, Vec3(0.1, 0.4, 0.2)}, {24, Vec3(0.5, 0.45, 0.1)}};
  setFinalTargets(doc, sidecar, targets, finalTargetFileName(dir.file("scene.json")));
  EXPECT_EQ(doc["task"]["loss"]["final"]["target"], "scene-final-target.npy");
  const Scene scene = parseScene(doc, dir.file("scene.json"), dir.path());
  const NodeMatrix rest = scene.cloths[0].mesh.vertices;
  writeTargetNpy(dir.file("scene-final-target.npy"), finalTargetMatrix(targets, rest));

  const NpyArray npy = readNpy(dir.file("scene-final-target.npy"));
  ASSERT_EQ(npy.shape, (std::vector<std::size_t>{25, 3}));
  EXPECT_EQ(npy.data[20 * 3 + 1], 0.4);
  EXPECT_EQ(npy.data[0], rest(0, 0)) << "vertices without a target keep their rest position";

  // The engine's loss on a trajectory that ends at the rest state: the squared distances.
  Trajectory t;
  t.positions = {rest, rest};
  const double expected = (rest.row(20) - targets[0].position.transpose()).squaredNorm() +
                          (rest.row(24) - targets[1].position.transpose()).squaredNorm();
  EXPECT_NEAR(TaskLoss(scene).value(scene, t), expected, 1e-15);

  // Opening the scene again makes the targets editable, to be written to the editor's own file.
  const nlohmann::json back = readFinalTargets(scene);
  const std::vector<FinalTarget> read = finalTargets(back);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[1].node, 24);
  EXPECT_EQ(read[1].position, targets[1].position);
  EXPECT_EQ(back["final_targets"]["file"], "scene-final-target.npy");
  // No file (yet): nothing to edit, and no error.
  nlohmann::json missing = doc;
  missing["task"]["loss"]["final"]["target"] = "absent.npy";
  EXPECT_TRUE(readFinalTargets(parseScene(missing, dir.file("scene.json"), dir.path())).empty());
}

TEST(LiveLoss, IsTheEngineLossOfTheCachedRun) {
  TempDir dir;
  nlohmann::json document = test::hangingClothScene(1.0, 4, 0.01, 6, 500.0);
  // A recorded motion: the same scene with a stiffer cloth.
  nlohmann::json stiffer = document;
  stiffer["cloths"][0]["material"]["stretch"] = 900.0;
  const Scene recordScene = test::parse(stiffer);
  Simulator recorder(recordScene);
  Trajectory recorded;
  recorder.run(6, recorded);
  const std::vector<double> flat = recorded.flattenedPositions();
  writeNpy(dir.file("motion.npy"), {7, 25, 3}, flat.data());
  document["task"] = {{"loss", {{"trajectory", {{"target", "motion.npy"}}}}}};
  EditorDocument doc(document);
  doc.saveAs(dir.file("scene.json"));

  SimulationCache cache;
  LiveLoss live;
  EXPECT_FALSE(live.evaluate(doc, cache).available) << "no run yet";
  cache.start(doc.sharedScene(), 6);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done);
  const LossValue& value = live.evaluate(doc, cache);
  ASSERT_TRUE(value.available) << value.note;

  Simulator simulator(*doc.scene());
  Trajectory own;
  simulator.run(6, own);
  const double engine = TaskLoss(*doc.scene()).value(*doc.scene(), own);
  EXPECT_GT(engine, 0.0);
  // The worker may use another OpenMP thread count than this test: agreement to rounding.
  EXPECT_NEAR(value.total, engine, 1e-9 * engine);

  // Targets held by the editor add a final term, computed from memory (no file written).
  const NodeMatrix& last = own.positions.back();
  const Vec3 target = last.row(22).transpose() + Vec3(0, 0.1, 0);
  ASSERT_EQ(doc.editWithSidecar("t",
                                [&](nlohmann::json& d, nlohmann::json& s) {
                                  setFinalTargets(d, s, {{22, target}}, "scene-final-target.npy");
                                }),
            "");
  EXPECT_FALSE(cache.staleFor(doc.document())) << "targets do not change the motion";
  const LossValue& both = live.evaluate(doc, cache);
  ASSERT_TRUE(both.available) << both.note;
  ASSERT_EQ(both.terms.size(), 2u);
  EXPECT_NEAR(both.total, engine + 0.01, 1e-9);

  // A motion edit makes the run stale: no loss until it is simulated again.
  doc.setValue("cloths.0.material.stretch", 600.0);
  EXPECT_FALSE(live.evaluate(doc, cache).available);
}

// A handle_clearance term (diff/HandleClearanceLoss.h) is a term of the scene, not of the motion:
// the live loss lists it beside the motion's terms with the engine's value.
TEST(LiveLoss, ListsTheHandleClearanceTermWithTheEngineValue) {
  TempDir dir;
  nlohmann::json document = test::hangingClothScene(1.0, 4, 0.01, 6, 500.0);
  // Top corner 4 (at x = 0.5, y = 1.5) on a handle held still, 1 cm inside a sphere.
  document["cloths"][0]["attachments"] = nlohmann::json::array(
      {{{"vertices", {0}}, {"kind", "fixed"}},
       {{"vertices", {4}},
        {"kind", "handle"},
        {"trajectory", {{"keyframes", {{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}}}}}}}});
  nlohmann::json sphere;
  sphere["sphere"]["center"] = {0.5, 1.5, 0.09};
  sphere["sphere"]["radius"] = 0.1;
  document["obstacles"] = nlohmann::json::array({sphere});
  document["task"]["loss"]["keypoints"]["points"] =
      nlohmann::json::array({{{"step", 6}, {"vertices", {12}}, {"positions", {{0.0, 0.5, 0.0}}}}});
  document["task"]["loss"]["handle_clearance"] = {{"weight", 2.0}};
  EditorDocument doc(document);
  doc.saveAs(dir.file("scene.json"));

  SimulationCache cache;
  LiveLoss live;
  cache.start(doc.sharedScene(), 6);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done);
  const LossValue& value = live.evaluate(doc, cache);
  ASSERT_TRUE(value.available) << value.note;
  ASSERT_EQ(value.terms.size(), 2u);
  EXPECT_EQ(value.terms[1].first, "handle_clearance");
  // 2 /s x 6 steps x 0.01 s x (1 cm)^2.
  EXPECT_NEAR(value.terms[1].second, 2.0 * 6 * 0.01 * 1e-4, 1e-12);
  Simulator simulator(*doc.scene());
  Trajectory own;
  simulator.run(6, own);
  const double engine = TaskLoss(*doc.scene()).value(*doc.scene(), own);
  EXPECT_NEAR(value.total, engine, 1e-9 * engine);
}

}  // namespace
}  // namespace weft::editor
