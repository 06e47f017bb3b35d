// Unsaved work survives a crash: the autosave writes a dirty document (at most every interval
// seconds while it changes), removes its file once the document is clean, saved elsewhere or
// discarded, and a later run restores it as unsaved changes over the scene file. Plain classes
// here; the prompt of a second editor run in EditorRobustnessScriptTest.cpp.

#include <Autosave.h>
#include <EditorSession.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// What another run would find in the folder.
std::vector<Recovery> found(const std::string& folder) {
  return Autosave(folder).recoveries();
}

// A small saved scene, drape.json, of stretch 500 N/m.
std::string drapeScene(const TempDir& dir) {
  return test::writeScene(dir.file("drape.json"), test::hangingClothScene(1.0, 4, 0.01, 5, 500.0));
}

// A document opened from `scene` and changed to `stretch`, autosaved to `folder`.
void editAndAutosave(Autosave& autosave, EditorDocument& doc, const std::string& scene,
                     double stretch) {
  doc.open(scene);
  ASSERT_EQ(doc.setValue("cloths.0.material.stretch", stretch), "");
  autosave.tick(doc, 0.0);
}

TEST(Autosave, WritesADirtyDocumentAtMostEveryIntervalAndRemovesItWhenClean) {
  TempDir dir;
  const std::string folder = dir.file("recovery");
  Autosave autosave(folder, 5.0);
  EditorDocument doc;
  autosave.tick(doc, 1.0);
  EXPECT_TRUE(found(folder).empty()) << "a clean document is not written";
  ASSERT_EQ(doc.setValue("time.steps", 7), "");
  EXPECT_TRUE(autosave.pending(doc));
  autosave.tick(doc, 0.1);  // the first change is written at once
  EXPECT_FALSE(autosave.pending(doc));
  std::vector<Recovery> r = found(folder);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].sceneFile, "") << "untitled";
  EXPECT_EQ(r[0].document["time"]["steps"], 7);
  EXPECT_NE(r[0].path.find("untitled-"), std::string::npos) << r[0].path;

  ASSERT_EQ(doc.setValue("time.steps", 8), "");
  autosave.tick(doc, 1.0);  // within the interval: waits
  EXPECT_TRUE(autosave.pending(doc));
  EXPECT_EQ(found(folder)[0].document["time"]["steps"], 7);
  autosave.tick(doc, 4.5);
  EXPECT_FALSE(autosave.pending(doc));
  EXPECT_EQ(found(folder)[0].document["time"]["steps"], 8);

  // Undone to the state it started from: clean, nothing to recover.
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  ASSERT_FALSE(doc.dirty());
  autosave.tick(doc, 0.1);
  EXPECT_TRUE(found(folder).empty());
  EXPECT_FALSE(Autosave().enabled()) << "no folder: off";
}

TEST(Autosave, ASavedSceneHasItsOwnRecoveryWhichSavingOrDiscardingRemoves) {
  TempDir dir;
  const std::string folder = dir.file("recovery");
  const std::string scene = drapeScene(dir);
  Autosave autosave(folder, 0.0);
  EditorDocument doc;
  editAndAutosave(autosave, doc, scene, 400.0);
  std::vector<Recovery> r = found(folder);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(fs::path(r[0].sceneFile), fs::absolute(scene).lexically_normal());
  EXPECT_EQ(fs::path(r[0].path).filename().string().rfind("drape-", 0), 0u) << r[0].path;
  EXPECT_FALSE(r[0].savedAt.empty());
  doc.save();
  autosave.tick(doc, 0.0);
  EXPECT_TRUE(found(folder).empty()) << "saved: nothing to recover";
  ASSERT_EQ(doc.setValue("time.steps", 10), "");
  autosave.tick(doc, 0.0);
  ASSERT_EQ(found(folder).size(), 1u);
  autosave.discardCurrent();
  EXPECT_TRUE(found(folder).empty()) << "discarded on purpose";
  // A damaged file is not offered.
  fs::create_directories(folder);
  std::ofstream(folder + "/broken.json") << "{\"document\": ";
  EXPECT_TRUE(found(folder).empty());
}

TEST(Autosave, RestoreOpensTheSceneAndPutsTheRecoveredDocumentOverItUnsaved) {
  TempDir dir;
  const std::string folder = dir.file("recovery");
  const std::string scene = drapeScene(dir);
  {
    Autosave autosave(folder, 0.0);
    EditorDocument doc;
    editAndAutosave(autosave, doc, scene, 321.0);
  }  // the run ends without saving (as in a crash)
  const std::vector<Recovery> r = found(folder);
  ASSERT_EQ(r.size(), 1u);
  EditorSession session("");
  ASSERT_EQ(session.restore(r[0]), "");
  const EditorDocument& doc = session.document();
  EXPECT_EQ(fs::path(doc.file()), fs::absolute(scene).lexically_normal());
  EXPECT_TRUE(doc.dirty());
  EXPECT_EQ(doc.document()["cloths"][0]["material"]["stretch"], 321.0);
  EXPECT_TRUE(found(folder).empty()) << "the recovery file goes once restored";
  ASSERT_TRUE(session.document().undo());
  EXPECT_EQ(session.document().document()["cloths"][0]["material"]["stretch"], 500.0)
      << "undo gives back the file as saved";
}

}  // namespace
}  // namespace weft::editor
