// The editor's document model: validation through the real loader, edits by JSON path, undo
// and redo, the dirty flag, atomic saving and the recent-files list.

#include <EditorDocument.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/core/Error.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;

TEST(EditorDocument, DefaultSceneIsValidAndClean) {
  EditorDocument doc;
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  EXPECT_FALSE(doc.dirty());
  EXPECT_FALSE(doc.canUndo());
  EXPECT_EQ(doc.displayName(), "untitled");
  EXPECT_EQ(doc.scene()->vertexCount(), 17 * 17);
}

TEST(EditorDocument, SetValueEditsValidatesAndUndoes) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
  const long revision = doc.revision();
  EXPECT_EQ(doc.setValue("cloths.0.material.stretch", 250.0), "");
  EXPECT_TRUE(doc.dirty());
  EXPECT_GT(doc.revision(), revision);
  ASSERT_TRUE(doc.valid());
  EXPECT_DOUBLE_EQ(doc.scene()->cloths[0].material.stretch, 250.0);
  EXPECT_EQ(doc.undoLabel(), "Set cloths.0.material.stretch");

  ASSERT_TRUE(doc.undo());
  EXPECT_DOUBLE_EQ(doc.scene()->cloths[0].material.stretch, 100.0);
  EXPECT_FALSE(doc.dirty()) << "back at the state it started from";
  EXPECT_TRUE(doc.canRedo());
  ASSERT_TRUE(doc.redo());
  EXPECT_DOUBLE_EQ(doc.scene()->cloths[0].material.stretch, 250.0);
  EXPECT_TRUE(doc.dirty());
  EXPECT_FALSE(doc.redo());
}

TEST(EditorDocument, InvalidValueIsKeptAndReportedNeverClamped) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
  EXPECT_EQ(doc.setValue("time.dt", -0.5), "");  // the edit itself is well-formed
  EXPECT_FALSE(doc.valid());
  EXPECT_NE(doc.validationError().find("time.dt"), std::string::npos) << doc.validationError();
  EXPECT_EQ(doc.document()["time"]["dt"], -0.5) << "the value stays as typed";
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.valid());
  EXPECT_TRUE(doc.validationError().empty());
}

TEST(EditorDocument, WarnsOfAHandleDrivenIntoAnObstacleAndForgetsItWhenMovedOut) {
  // A handle on corner 0 of a 1 m cloth at the origin moves 1 m along +X over 1 s, through a
  // sphere of radius 0.2 at (0, 0, -0.5) (corner 0 rests at (-0.5, 0, -0.5)).
  nlohmann::json scene = test::gridScene(1.0, 4, 0.01, 100);
  scene["cloths"][0]["attachments"] = {
      {{"vertices", {0}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 1.0}, {"offset", {1.0, 0, 0}}}}}}}}};
  scene["obstacles"] = {
      {{"sphere", {{"center", {0, 0, -0.5}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  EditorDocument doc(scene);
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  ASSERT_EQ(doc.scene()->warnings.size(), 1u);
  EXPECT_NE(doc.scene()->warnings[0].find(
                "cloths.0.attachments.0: the handle's targets enter obstacles.0 (sphere)"),
            std::string::npos)
      << doc.scene()->warnings[0];
  // Moving the sphere off the handle's path clears the warning on the next validation.
  EXPECT_EQ(doc.setValue("obstacles.0.sphere.center", nlohmann::json::array({0, 0.5, -0.5})), "");
  ASSERT_TRUE(doc.valid());
  EXPECT_TRUE(doc.scene()->warnings.empty());
}

TEST(EditorDocument, MalformedEditsAreRefusedAndLeaveTheDocument) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
  const nlohmann::json before = doc.document();
  EXPECT_NE(doc.setValue("cloths.3.material.stretch", 1.0), "");
  EXPECT_NE(doc.setValue("time.dt", "fast"), "");
  EXPECT_NE(doc.setValue("gravity", nlohmann::json::array({1, 2})), "");
  EXPECT_NE(doc.removeValue("no_such_key"), "");
  EXPECT_EQ(doc.document(), before);
  EXPECT_FALSE(doc.canUndo());
  EXPECT_FALSE(doc.dirty());
}

TEST(EditorDocument, SetValueCreatesMissingParentsAndRemoveDropsModules) {
  EditorDocument doc(test::gridScene(1.0, 4, 0.01, 10));
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  EXPECT_EQ(doc.setValue("solver.pd_iterations", 42), "");
  ASSERT_TRUE(doc.valid()) << doc.validationError();
  EXPECT_EQ(doc.scene()->solver.pdIterations, 42);
  EXPECT_EQ(doc.setValue("gravity", nlohmann::json::array({0.0, -9.8, 0.0})), "");
  ASSERT_TRUE(doc.scene()->gravity.has_value());
  EXPECT_EQ(doc.removeValue("gravity"), "");
  EXPECT_FALSE(doc.scene()->gravity.has_value());
}

TEST(EditorDocument, CoalescedEditsAreOneUndoStep) {
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
  doc.setValue("cloths.0.material.stretch", 110.0, false);
  doc.setValue("cloths.0.material.stretch", 120.0, true);
  doc.setValue("cloths.0.material.stretch", 130.0, true);
  doc.setValue("cloths.0.material.density", 0.3, true);  // another path: a new step
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_DOUBLE_EQ(doc.scene()->cloths[0].material.stretch, 100.0);
  EXPECT_FALSE(doc.canUndo());
}

TEST(EditorDocument, EditWithAFailingChangeIsRefused) {
  EditorDocument doc;
  const nlohmann::json before = doc.document();
  const std::string error =
      doc.edit("Break", [](nlohmann::json& d) { d.at("missing").push_back(1); });
  EXPECT_NE(error.find("Break"), std::string::npos);
  EXPECT_EQ(doc.document(), before);
}

TEST(EditorDocument, SaveIsAtomicAndRoundTrips) {
  test::TempDir dir;
  EditorDocument doc(test::hangingClothScene(1.0, 4, 0.01, 10, 100.0));
  EXPECT_THROW(doc.save(), InputError) << "a new document has no file";
  doc.setValue("cloths.0.material.bend", 0.002);
  const std::string file = dir.file("scene.json");
  doc.saveAs(file);
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(doc.file(), file);
  // Nothing but the scene is left in the folder (no temporary files).
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    ++entries;
    EXPECT_EQ(e.path().filename(), "scene.json");
  }
  EXPECT_EQ(entries, 1);

  EditorDocument reopened;
  reopened.open(file);
  EXPECT_EQ(reopened.document(), doc.document());
  EXPECT_TRUE(reopened.valid()) << reopened.validationError();
  EXPECT_FALSE(reopened.canUndo()) << "opening starts a fresh history";

  // Saving again replaces the file in one step.
  doc.setValue("cloths.0.material.bend", 0.004);
  EXPECT_TRUE(doc.dirty());
  doc.save();
  reopened.open(file);
  EXPECT_EQ(reopened.document()["cloths"][0]["material"]["bend"], 0.004);
}

TEST(EditorDocument, FailedSaveLeavesTheTargetAndNoTemporaryFile) {
  test::TempDir dir;
  EditorDocument doc;
  EXPECT_THROW(doc.saveAs(dir.file("missing-folder/scene.json")), InputError);
  EXPECT_TRUE(doc.file().empty());
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(EditorDocument, OpenRejectsBrokenFilesAndKeepsTheDocument) {
  test::TempDir dir;
  EditorDocument doc;
  const nlohmann::json before = doc.document();
  EXPECT_THROW(doc.open(dir.file("nope.json")), InputError);
  EXPECT_THROW(doc.open(dir.write("bad.json", "{ not json")), InputError);
  // A number beyond double's range is nlohmann's out_of_range, not a parse_error (found by the
  // editor_script fuzzer in the script reader, which read files the same way).
  EXPECT_THROW(doc.open(dir.write("overflow.json", R"({"time": {"dt": 1e400}})")), InputError);
  EXPECT_EQ(doc.document(), before);
  // Valid JSON that the loader rejects is opened, with the loader's message.
  doc.open(dir.write("invalid.json",
                     R"({"time": {"dt": 0.01, "steps": 5}, "cloths": [], "colour": 1})"));
  EXPECT_FALSE(doc.valid());
  EXPECT_FALSE(doc.validationError().empty());
}

TEST(RecentFiles, MostRecentFirstWithoutDuplicatesPersisted) {
  test::TempDir dir;
  const std::string store = dir.file("config/recent.json");
  {
    RecentFiles recent(store, 3);
    recent.add(dir.file("a.json"));
    recent.add(dir.file("b.json"));
    recent.add(dir.file("a.json"));
    recent.add(dir.file("c.json"));
    recent.add(dir.file("d.json"));
    ASSERT_EQ(recent.files().size(), 3u);
    EXPECT_EQ(recent.files()[0], dir.file("d.json"));
    EXPECT_EQ(recent.files()[1], dir.file("c.json"));
    EXPECT_EQ(recent.files()[2], dir.file("a.json"));
  }
  RecentFiles again(store, 3);
  ASSERT_EQ(again.files().size(), 3u);
  EXPECT_EQ(again.files()[0], dir.file("d.json"));
  RecentFiles damaged(dir.write("broken.json", "[1, 2"), 3);
  EXPECT_TRUE(damaged.files().empty());
}

}  // namespace
}  // namespace weft::editor
