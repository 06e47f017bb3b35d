// ./run.sh builds only what its main job runs: `weft`, plus `weft-editor` when it opens the
// editor (a display and no WEFT_HEADLESS, no scene argument); never the tests or the generated
// task targets, which only test.sh needs. Checked through the script's own dry run
// (WEFT_DRY_RUN=1 prints the build command weft_build would run, and stops), so changing run.sh
// back to building everything fails here.

#include "CliSupport.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <sstream>

namespace weft {
namespace {

using test::describe;
using test::runProcess;

// The targets of the one build command a dry run of `script` prints, with `environment`
// (NAME=VALUE entries) on top of one without DISPLAY, WEFT_HEADLESS and WEFT_BUILD_DIR.
// `everything` is set when the command names no target (cmake then builds all of them).
std::set<std::string> builtTargets(const std::vector<std::string>& command,
                                   const std::vector<std::string>& environment, bool& everything) {
  std::vector<std::string> argv{"/usr/bin/env",  "-u", "DISPLAY",        "-u",
                                "WEFT_HEADLESS", "-u", "WEFT_BUILD_DIR", "WEFT_DRY_RUN=1"};
  argv.insert(argv.end(), environment.begin(), environment.end());
  argv.insert(argv.end(), command.begin(), command.end());
  const test::ProcessResult r = runProcess(argv);
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = test::splitLines(r.out);
  EXPECT_EQ(lines.size(), 1u) << describe(r);
  std::set<std::string> targets;
  everything = true;
  if (lines.empty()) return targets;
  std::istringstream words(lines[0]);
  std::vector<std::string> w;
  for (std::string s; words >> s;) w.push_back(s);
  EXPECT_GE(w.size(), 3u) << lines[0];
  if (w.size() >= 3) {
    EXPECT_EQ(w[0], "cmake") << lines[0];
    EXPECT_EQ(w[1], "--build") << lines[0];
  }
  for (std::size_t i = 0; i < w.size(); ++i)
    if (w[i] == "--target") {
      everything = false;
      for (std::size_t j = i + 1; j < w.size() && w[j].rfind("-", 0) != 0; ++j)
        targets.insert(w[j]);
    }
  return targets;
}

std::vector<std::string> runScript(std::vector<std::string> args = {}) {
  std::vector<std::string> command{"bash", std::string(WEFT_SOURCE_DIR) + "/run.sh"};
  command.insert(command.end(), args.begin(), args.end());
  return command;
}

TEST(RunScript, HeadlessBuildsTheWeftToolOnly) {
  bool everything = true;
  EXPECT_EQ(builtTargets(runScript(), {}, everything), std::set<std::string>{"weft"});
  EXPECT_FALSE(everything);
  EXPECT_EQ(builtTargets(runScript(), {"DISPLAY=:99", "WEFT_HEADLESS=1"}, everything),
            std::set<std::string>{"weft"});
  EXPECT_FALSE(everything);
}

TEST(RunScript, WithADisplayItAlsoBuildsTheEditor) {
  bool everything = true;
  EXPECT_EQ(builtTargets(runScript(), {"DISPLAY=:99"}, everything),
            (std::set<std::string>{"weft", "weft-editor"}));
  EXPECT_FALSE(everything);
}

TEST(RunScript, ASceneArgumentSimulatesHeadlessAndBuildsTheWeftToolOnly) {
  bool everything = true;
  EXPECT_EQ(builtTargets(runScript({"assets/scenes/slope.json", "out/slope"}), {"DISPLAY=:99"},
                         everything),
            std::set<std::string>{"weft"});
  EXPECT_FALSE(everything);
}

TEST(RunScript, TestScriptsBuildStillBuildsEverything) {
  // test.sh calls weft_build without targets: every target, the tests included.
  bool everything = false;
  const std::set<std::string> targets = builtTargets(
      {"bash", "-c",
       "source \"$0\"/scripts/ensure-deps.sh && weft_build && grep -qx 'weft_build' \"$0\"/test.sh",
       WEFT_SOURCE_DIR},
      {}, everything);
  EXPECT_TRUE(everything);
  EXPECT_TRUE(targets.empty());
}

}  // namespace
}  // namespace weft
