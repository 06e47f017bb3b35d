// Output folders appear only when complete: a failing run never replaces or touches an
// existing output folder, and leaves no temporary folder behind.

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::readFile;
using test::TempDir;

std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(StagedDirectory, CommitMovesTheFilesIntoPlace) {
  TempDir dir;
  const std::string out = dir.file("run");
  {
    StagedDirectory staged(out);
    std::ofstream(staged.file("a.txt")) << "new";
    EXPECT_FALSE(fs::exists(out)) << "visible before commit";
    staged.commit();
  }
  EXPECT_EQ(readFile(out + "/a.txt"), "new");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"run"});
}

TEST(StagedDirectory, CommitReplacesAnExistingFolderWhole) {
  TempDir dir;
  const std::string out = dir.write("run/old.txt", "old");
  (void)out;
  {
    StagedDirectory staged(dir.file("run"));
    std::ofstream(staged.file("a.txt")) << "new";
    EXPECT_EQ(readFile(dir.file("run/old.txt")), "old");
    staged.commit();
  }
  EXPECT_EQ(entries(dir.file("run")), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"run"});
}

TEST(StagedDirectory, AbandonedStagingLeavesTheOldFolderUntouched) {
  TempDir dir;
  dir.write("run/sentinel.txt", "keep me");
  {
    StagedDirectory staged(dir.file("run"));
    std::ofstream(staged.file("partial.npy")) << "partial";
    // No commit: as when the simulation throws.
  }
  EXPECT_EQ(entries(dir.file("run")), std::vector<std::string>{"sentinel.txt"});
  EXPECT_EQ(readFile(dir.file("run/sentinel.txt")), "keep me");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"run"}) << "stray staging folder";
}

TEST(StagedDirectory, RefusesAFileInTheWay) {
  TempDir dir;
  dir.write("run", "a file, not a folder");
  EXPECT_THROW(StagedDirectory staged(dir.file("run")), InputError);
  EXPECT_EQ(readFile(dir.file("run")), "a file, not a folder");
}

TEST(StagedDirectory, CreatesMissingParents) {
  TempDir dir;
  {
    StagedDirectory staged(dir.file("a/b/run/"));
    std::ofstream(staged.file("x")) << "1";
    staged.commit();
  }
  EXPECT_EQ(readFile(dir.file("a/b/run/x")), "1");
}

}  // namespace
}  // namespace weft
