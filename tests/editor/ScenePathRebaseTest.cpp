// Save As into another folder: relative file references (meshes, task targets) are rewritten to
// name the same files from the new folder, in the saved file, the document and its undo history;
// the scene then loads from there through the engine's own loader. The editor's own target file
// is written next to the new scene instead, and a current simulation stays current.

#include <EditorDocument.h>
#include <EditorSession.h>
#include <ScenePathRebase.h>

#include "EditorScriptRun.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/diff/TaskLoss.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;
using test::readJson;
using test::TempDir;

// A 2 x 1 m strip in the XZ plane: six vertices, four triangles.
const char* kStripObj =
    "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 1\nv 1 0 1\nv 2 0 1\nf 1 4 5\nf 1 5 2\nf 2 5 6\nf 2 6 3\n";

// The hanging cloth plus a cloth and a mesh obstacle read from `mesh` (as the scene names it).
nlohmann::json sceneWithMesh(const std::string& mesh) {
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 0.01, 3, 500.0);
  doc["cloths"].push_back(
      {{"mesh", {{"file", mesh}, {"transform", {{"translate", {0.0, 2.0, 0.0}}}}}},
       {"material", {{"density", 0.1}, {"stretch", 500.0}, {"bend", 0.0}}}});
  doc["obstacles"] = {{{"mesh", {{"file", mesh}}}, {"friction", 0.3}}};
  return doc;
}

TEST(ScenePathRebase, ListsEveryFileTheEngineResolvesAgainstTheScene) {
  nlohmann::json doc = sceneWithMesh("meshes/strip.obj");
  doc["obstacles"].push_back({{"sphere", {{"center", {0, 0, 0}}, {"radius", 0.1}}}});
  doc["task"] = {{"loss",
                  {{"trajectory", {{"target", "run/positions.npy"}}},
                   {"final", {{"target", "final.npy"}, {"vertices", {0}}}},
                   {"keypoints",
                    {{"points",
                      {{{"step", 1}, {"vertices", {0}}, {"target", "keys.npy"}},
                       {{"step", 2}, {"vertices", {1}}, {"positions", {{0, 0, 0}}}}}}}}}}};
  EXPECT_EQ(sceneFileReferences(doc),
            (std::vector<std::string>{"cloths.1.mesh.file", "obstacles.0.mesh.file",
                                      "task.loss.trajectory.target", "task.loss.final.target",
                                      "task.loss.keypoints.points.0.target"}));
}

TEST(ScenePathRebase, RelativeReferencesNameTheSameFilesFromTheNewFolder) {
  TempDir dir;
  const std::string from = dir.file("project"), to = dir.file("elsewhere/deeper");
  fs::create_directories(dir.file("project/meshes"));
  fs::create_directories(dir.file("project/run"));
  dir.write("project/meshes/strip.obj", kStripObj);
  dir.write("project/run/positions.npy", "");  // only its existence matters here
  dir.write("project/keys.npy", "");
  nlohmann::json doc = sceneWithMesh("meshes/strip.obj");
  doc["obstacles"][0]["mesh"]["file"] = "/data/absolute/head.obj";
  doc["task"] = {
      {"loss",
       {{"trajectory", {{"target", "./run/../run/positions.npy"}}},
        {"final", {{"target", "later/final.npy"}, {"vertices", {0}}}},
        {"keypoints", {{"points", {{{"step", 1}, {"vertices", {0}}, {"target", "keys.npy"}}}}}}}}};
  const nlohmann::json before = doc;

  // The same folder, however spelt: nothing changes, not even an unusual spelling.
  EXPECT_TRUE(rebaseSceneFiles(doc, from, from + "/./").empty());
  EXPECT_EQ(doc, before);

  const std::vector<std::string> changed =
      rebaseSceneFiles(doc, from, to, {"task.loss.keypoints.points.0.target"});
  EXPECT_EQ(changed,
            (std::vector<std::string>{"cloths.1.mesh.file", "task.loss.trajectory.target"}));
  EXPECT_EQ(doc["cloths"][1]["mesh"]["file"], "../../project/meshes/strip.obj");
  EXPECT_EQ(doc["obstacles"][0]["mesh"]["file"], "/data/absolute/head.obj")
      << "absolute stays absolute";
  EXPECT_EQ(doc["task"]["loss"]["trajectory"]["target"], "../../project/run/positions.npy");
  EXPECT_EQ(doc["task"]["loss"]["final"]["target"], "later/final.npy")
      << "names no file: kept as written";
  EXPECT_EQ(doc["task"]["loss"]["keypoints"]["points"][0]["target"], "keys.npy") << "kept as asked";

  // And back: the references are the original files again, named from their own folder.
  rebaseSceneFiles(doc, to, from);
  EXPECT_EQ(doc["cloths"][1]["mesh"]["file"], "meshes/strip.obj");
  EXPECT_EQ(doc["task"]["loss"]["trajectory"]["target"], "run/positions.npy");
}

TEST(ScenePathRebase, SaveAsElsewhereKeepsTheMeshFoundAndTheHistoryWithIt) {
  TempDir dir;
  fs::create_directories(dir.file("project/meshes"));
  fs::create_directories(dir.file("elsewhere/deeper"));
  const std::string mesh = dir.write("project/meshes/strip.obj", kStripObj);
  const std::string original =
      test::writeScene(dir.file("project/scene.json"), sceneWithMesh("meshes/strip.obj"));

  EditorDocument doc;
  doc.open(original);
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  ASSERT_EQ(doc.setValue("cloths.0.material.stretch", 250.0), "");
  const std::string copy = dir.file("elsewhere/deeper/copy.json");
  doc.saveAs(copy);

  // The saved file names the same mesh from its own folder, and the engine loads it from there.
  const nlohmann::json saved = readJson(copy);
  for (const char* path : {"cloths", "obstacles"}) {
    SCOPED_TRACE(path);
    const std::string reference =
        saved[path][path == std::string("cloths") ? 1 : 0]["mesh"]["file"];
    EXPECT_EQ(reference, "../../project/meshes/strip.obj");
    EXPECT_TRUE(fs::equivalent(fs::path(copy).parent_path() / reference, mesh));
  }
  const Scene loaded = loadScene(copy);
  EXPECT_EQ(loaded.cloths[1].mesh.vertexCount(), 6);
  EXPECT_EQ(loaded.obstacles[0].mesh.triangleCount(), 4);

  // The document is the file: clean, valid, equal.
  EXPECT_EQ(doc.document(), saved);
  EXPECT_FALSE(doc.dirty());
  ASSERT_TRUE(doc.valid()) << doc.validationError();

  // Undo goes back to before the edit without bringing back a reference that names nothing from
  // here: the history was rebased with the document.
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.document()["cloths"][0]["material"]["stretch"], 500.0);
  EXPECT_EQ(doc.document()["cloths"][1]["mesh"]["file"], "../../project/meshes/strip.obj");
  EXPECT_TRUE(doc.valid()) << doc.validationError();
  ASSERT_TRUE(doc.redo());
  EXPECT_FALSE(doc.dirty()) << "back at the saved state";

  // Saved back beside the mesh, the reference is the short one again.
  doc.saveAs(dir.file("project/again.json"));
  EXPECT_EQ(readJson(dir.file("project/again.json"))["cloths"][1]["mesh"]["file"],
            "meshes/strip.obj");
}

// project/scene.json naming project/meshes/strip.obj, opened in `session` with a final target at
// vertex 3. Returns the scene's path.
std::string openProjectWithTarget(const TempDir& dir, EditorSession& session) {
  fs::create_directories(dir.file("project/meshes"));
  dir.write("project/meshes/strip.obj", kStripObj);
  const std::string original =
      test::writeScene(dir.file("project/scene.json"), sceneWithMesh("meshes/strip.obj"));
  session.open(original);
  EXPECT_TRUE(session.document().valid()) << session.document().validationError();
  EXPECT_EQ(session.targets().setTarget(3, Vec3(0.1, 0.2, 0.3)), "");
  return original;
}

TEST(ScenePathRebase, SessionSaveAsWritesItsTargetsBesideTheNewSceneAndKeepsTheRunCurrent) {
  TempDir dir;
  fs::create_directories(dir.file("elsewhere"));
  EditorSession session("");
  openProjectWithTarget(dir, session);
  ASSERT_EQ(session.timeline().simulate(2), "");
  session.cache().wait();
  ASSERT_EQ(session.cache().status(), SimulationCache::Status::Done) << session.cache().error();
  ASSERT_FALSE(session.timeline().cacheStale());

  const std::string copy = dir.file("elsewhere/copy.json");
  EXPECT_EQ(session.saveAs(copy), "");
  const nlohmann::json saved = readJson(copy);
  EXPECT_EQ(saved["cloths"][1]["mesh"]["file"], "../project/meshes/strip.obj");
  // The editor's own target file goes with the scene (written beside it, named after it).
  EXPECT_EQ(saved["task"]["loss"]["final"]["target"], "copy-final-target.npy");
  EXPECT_TRUE(fs::is_regular_file(dir.file("elsewhere/copy-final-target.npy")));
  EXPECT_FALSE(fs::exists(dir.file("project/scene-final-target.npy")))
      << "nothing written to the old folder";
  // The engine builds the task from the new place (the target file read and shape-checked).
  const Scene loaded = loadScene(copy);
  EXPECT_NO_THROW(TaskLoss{loaded});

  EXPECT_FALSE(session.timeline().cacheStale()) << "the same files, so the same run";
  EXPECT_EQ(session.timeline().availableFrames(), 3);
}

// Save As beside the original: the copy gets its own target file, so editing the copy's targets
// never rewrites the original's (both used to name scene-final-target.npy).
TEST(ScenePathRebase, SaveAsBesideTheOriginalGivesTheCopyItsOwnTargetFile) {
  TempDir dir;
  EditorSession session("");
  const std::string original = openProjectWithTarget(dir, session);
  ASSERT_EQ(session.save(), "");
  const std::string originalTargets = test::readFile(dir.file("project/scene-final-target.npy"));

  const std::string copy = dir.file("project/copy.json");
  ASSERT_EQ(session.saveAs(copy), "");
  EXPECT_EQ(readJson(copy)["task"]["loss"]["final"]["target"], "copy-final-target.npy");
  EXPECT_EQ(test::readFile(dir.file("project/copy-final-target.npy")), originalTargets)
      << "the same targets, in the copy's own file";
  ASSERT_EQ(session.targets().setTarget(3, Vec3(0.4, 0.5, 0.6)), "");
  ASSERT_EQ(session.save(), "");
  EXPECT_NE(test::readFile(dir.file("project/copy-final-target.npy")), originalTargets);
  EXPECT_EQ(test::readFile(dir.file("project/scene-final-target.npy")), originalTargets)
      << "the original's targets are untouched";
  EXPECT_EQ(readJson(original)["task"]["loss"]["final"]["target"], "scene-final-target.npy");
  EXPECT_NO_THROW(TaskLoss{loadScene(copy)});
}

}  // namespace
}  // namespace weft::editor
