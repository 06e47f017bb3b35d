// `weft landscape` through the real binary: the loss grid of the wind system identification
// (its minimum, ~0, at the values that generated the target), the 1-D variant, and the exits of
// bad input (2).

#include <app/CliSupport.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using test::splitCommas;
using test::splitLines;
using test::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kScene = std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json";
const char* kStretch = "cloths.0.material.stretch";
const char* kWind = "wind.strength";

TEST(LandscapeCli, GridMinimumIsAtTheGeneratingValues) {
  TempDir dir;
  const std::string out = dir.file("land");
  const auto r =
      runWeft({"landscape", kScene, "--param", kStretch, "--param", kWind, "--grid", "3", "--range",
               std::string(kStretch) + "=200:300", "--range", std::string(kWind) + "=1.5:2.5",
               "--out", out, "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, StartsWith("landscape: wind_sysid: 9 points"));
  const auto lines = splitLines(test::readFile(out + "/landscape.csv"));
  ASSERT_EQ(lines.size(), 10u);
  EXPECT_EQ(lines[0], std::string(kStretch) + "," + kWind + ",loss");
  double minLoss = 1e300, maxLoss = 0.0, atStretch = 0.0, atWind = 0.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = splitCommas(lines[i]);
    ASSERT_EQ(f.size(), 3u) << lines[i];
    const double s = std::stod(f[0]), w = std::stod(f[1]), loss = std::stod(f[2]);
    // A varies slowest: 200,200,200,250,...; B cycles 1.5,2,2.5.
    EXPECT_DOUBLE_EQ(s, 200.0 + 50.0 * ((i - 1) / 3));
    EXPECT_DOUBLE_EQ(w, 1.5 + 0.5 * ((i - 1) % 3));
    EXPECT_GE(loss, 0.0);
    if (loss < minLoss) minLoss = loss, atStretch = s, atWind = w;
    maxLoss = std::max(maxLoss, loss);
  }
  EXPECT_DOUBLE_EQ(atStretch, 250.0);
  EXPECT_DOUBLE_EQ(atWind, 2.0);
  EXPECT_LT(minLoss, 1e-6 * maxLoss) << "the target was simulated at (250, 2.0)";
  EXPECT_TRUE(std::filesystem::exists(out + "/landscape.png") ||
              r.err.find("gnuplot") != std::string::npos);
}

TEST(LandscapeCli, OneParameterGivesALineWithDefaultRange) {
  TempDir dir;
  const std::string out = dir.file("line");
  const auto r = runWeft({"landscape", kScene, "--param", kWind, "--grid", "3", "--out", out,
                          "--quiet", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = splitLines(test::readFile(out + "/landscape.csv"));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], std::string(kWind) + ",loss");
  // The default range is [0.5, 1.5] x the scene's value (1.5).
  EXPECT_DOUBLE_EQ(std::stod(splitCommas(lines[1])[0]), 0.75);
  EXPECT_DOUBLE_EQ(std::stod(splitCommas(lines[2])[0]), 1.5);
  EXPECT_DOUBLE_EQ(std::stod(splitCommas(lines[3])[0]), 2.25);
}

struct BadLandscape {
  const char* name;
  std::vector<std::string> args;
  const char* where;
  const char* phrase;
};

TEST(LandscapeCli, BadInputExitsTwoAndKeepsAnExistingOutput) {
  TempDir dir;
  const std::string out = dir.file("kept");
  std::filesystem::create_directories(out);
  dir.write("kept/landscape.csv", "good\n");
  const std::string s = kStretch, w = kWind;
  const BadLandscape cases[] = {
      {"NoParam", {kScene}, "--param: ", "one or two parameters"},
      {"ThreeParams",
       {kScene, "--param", s, "--param", w, "--param", "wind.frequency"},
       "--param: ",
       "one or two parameters"},
      {"SameParamTwice", {kScene, "--param", s, "--param", s}, "--param: ", "must differ"},
      {"UnknownPath", {kScene, "--param", s, "--param", "wind.nope"}, "wind.nope: ", ""},
      {"GridOne", {kScene, "--param", s, "--param", w, "--grid", "1"}, "--grid: ", ""},
      {"GridText", {kScene, "--param", s, "--param", w, "--grid", "ten"}, "--grid: ", ""},
      {"RangeReversed",
       {kScene, "--param", s, "--param", w, "--range", s + "=300:200"},
       "--range ",
       "LO < HI"},
      {"RangeMalformed",
       {kScene, "--param", s, "--param", w, "--range", s + "=abc"},
       "--range ",
       "PATH=LO:HI"},
      {"RangeNotNumbers",
       {kScene, "--param", s, "--param", w, "--range", s + "=a:b"},
       "--range ",
       "numbers"},
      {"RangeOtherPath",
       {kScene, "--param", s, "--param", w, "--range", "wind.phase=0:1"},
       "--range wind.phase: ",
       "not one of the --param"},
      {"RangeInvalidValue",
       {kScene, "--param", s, "--param", w, "--grid", "2", "--range", s + "=-10:100"},
       "at grid point",
       ""},
  };
  for (const BadLandscape& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--out", out, "--quiet"});
    test::expectBadInput("landscape", args, c.where, c.phrase);
    EXPECT_EQ(test::readFile(out + "/landscape.csv"), "good\n");
  }
}

}  // namespace
}  // namespace weft
