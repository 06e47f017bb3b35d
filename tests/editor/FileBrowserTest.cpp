// The file dialogs' browser as a plain class: what a folder lists and in which order, moving
// between folders, refusing a folder that cannot be listed without losing the one shown, and the
// places to start from.

#include "FileBrowser.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::vector<std::string> names(const FileBrowser& b) {
  std::vector<std::string> out;
  for (const FileEntry& e : b.entries()) out.push_back(e.folder ? e.name + "/" : e.name);
  return out;
}

// dir/ holds meshes of mixed case, other files, hidden entries and two folders.
void fill(const TempDir& dir) {
  for (const char* f : {"b.obj", "A.obj", "D.OBJ", "c.txt", "scene.json", ".hidden.obj"})
    dir.write(f, "x");
  for (const char* d : {"Sub", "alpha", ".git"}) fs::create_directories(dir.file(d));
  dir.write("Sub/inner.obj", "x");
}

TEST(FileBrowser, ListsParentFoldersThenFilesOfItsKindsInCaseInsensitiveOrder) {
  TempDir dir;
  fill(dir);
  FileBrowser meshes({".obj"});
  ASSERT_TRUE(meshes.show(dir.path())) << meshes.error();
  EXPECT_EQ(names(meshes),
            (std::vector<std::string>{"../", "alpha/", "Sub/", "A.obj", "b.obj", "D.OBJ"}));
  EXPECT_TRUE(meshes.error().empty());
  FileBrowser everything;
  ASSERT_TRUE(everything.show(dir.path()));
  EXPECT_EQ(names(everything), (std::vector<std::string>{"../", "alpha/", "Sub/", "A.obj", "b.obj",
                                                         "c.txt", "D.OBJ", "scene.json"}));
  EXPECT_TRUE(meshes.lists("x.Obj"));
  EXPECT_FALSE(meshes.lists("x.obj.txt"));
}

TEST(FileBrowser, MovesIntoFoldersAndUpAgain) {
  TempDir dir;
  fill(dir);
  FileBrowser b({".obj"});
  // A trailing slash and a dot part are normalised away, so Up goes to the real parent.
  ASSERT_TRUE(b.show(dir.path() + "/./"));
  const fs::path top = b.folder();
  EXPECT_EQ(top, fs::path(dir.path()).lexically_normal());
  ASSERT_TRUE(b.enter({"Sub", true}));
  EXPECT_EQ(b.folder(), top / "Sub");
  EXPECT_EQ(names(b), (std::vector<std::string>{"../", "inner.obj"}));
  EXPECT_EQ(b.pathOf(b.entries()[1]), (top / "Sub" / "inner.obj").string());
  EXPECT_FALSE(b.enter({"inner.obj", false})) << "a file is not entered";
  ASSERT_TRUE(b.enter({"..", true}));
  EXPECT_EQ(b.folder(), top);
  ASSERT_TRUE(b.up());
  EXPECT_EQ(b.folder(), top.parent_path());
  ASSERT_TRUE(b.show("/"));
  EXPECT_TRUE(b.entries().empty() || b.entries()[0].name != "..") << "the root has no parent";
  EXPECT_FALSE(b.up());
}

TEST(FileBrowser, AFolderThatCannotBeListedIsRefusedAndTheShownOneKept) {
  TempDir dir;
  fill(dir);
  FileBrowser b({".obj"});
  ASSERT_TRUE(b.show(dir.path()));
  const std::vector<std::string> before = names(b);
  EXPECT_FALSE(b.show(dir.file("missing")));
  EXPECT_NE(b.error().find("missing"), std::string::npos) << b.error();
  EXPECT_FALSE(b.show(dir.file("b.obj"))) << "a file is not a folder";
  EXPECT_EQ(b.folder(), fs::path(dir.path()).lexically_normal());
  EXPECT_EQ(names(b), before);
  ASSERT_TRUE(b.show(dir.path()));
  EXPECT_TRUE(b.error().empty()) << "a good listing clears the error";
}

TEST(FileBrowser, ShowsTheFolderAPathFieldNames) {
  TempDir dir;
  fill(dir);
  FileBrowser b;
  ASSERT_TRUE(b.showFolderOf(dir.file("Sub")));
  EXPECT_EQ(b.folder().filename(), "Sub");
  ASSERT_TRUE(b.showFolderOf(dir.file("not-yet-saved.json"))) << "Save As names a new file";
  EXPECT_EQ(b.folder(), fs::path(dir.path()).lexically_normal());
  EXPECT_FALSE(b.showFolderOf(dir.file("missing/scene.json")));
  EXPECT_FALSE(b.showFolderOf(""));
}

TEST(FileBrowser, PlacesAreTheWorkingDirectorySceneFolderRecentFoldersAndHome) {
  TempDir dir;
  fill(dir);
  const fs::path cwd = fs::current_path();
  const std::vector<std::string> places = browsePlaces(
      dir.file("Sub/scene.json"), {dir.file("alpha/a.json"), dir.file("Sub/other.json"),
                                   dir.file("gone/x.json"), cwd.string() + "/y.json"});
  ASSERT_GE(places.size(), 3u);
  EXPECT_EQ(places[0], cwd.lexically_normal().string());
  EXPECT_EQ(places[1], (fs::path(dir.path()).lexically_normal() / "Sub").string());
  EXPECT_EQ(places[2], (fs::path(dir.path()).lexically_normal() / "alpha").string());
  for (const std::string& p : places) EXPECT_EQ(p.find("gone"), std::string::npos) << p;
  std::vector<std::string> sorted = places;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "no duplicates";
  if (const char* home = std::getenv("HOME"); home && fs::is_directory(home)) {
    EXPECT_NE(std::find(places.begin(), places.end(), fs::path(home).lexically_normal().string()),
              places.end());
  }
}

}  // namespace
}  // namespace weft::editor
