// `weft gradcheck` through the real binary: the text table and the --json list of the spec, and
// the exit codes of bad input (2) and of a backward pass that cannot be solved (3).

#include <app/CliSupport.h>
#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using test::splitLines;
using test::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kScene = std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json";

TEST(GradcheckCli, PrintsOneLinePerParameterAndASummary) {
  const auto r = runWeft({"gradcheck", kScene, "--param", "cloths.0.material.stretch", "--param",
                          "wind.strength", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  for (int i = 0; i < 2; ++i) {
    std::istringstream in(lines[i]);
    std::string param, k1, k2, k3;
    double adjoint = 0, fd = 0, rel = 1;
    in >> param >> k1 >> adjoint >> k2 >> fd >> k3 >> rel;
    EXPECT_EQ(param, i == 0 ? "cloths.0.material.stretch" : "wind.strength");
    EXPECT_EQ(k1, "adjoint");
    EXPECT_EQ(k2, "finite_difference");
    EXPECT_EQ(k3, "relative_error");
    EXPECT_NE(adjoint, 0.0);
    EXPECT_LT(rel, 1e-4) << lines[i];
  }
  EXPECT_THAT(lines[2], StartsWith("gradcheck: wind_sysid: 2 parameters"));
  EXPECT_THAT(lines[2], HasSubstr("fallbacks"));
}

TEST(GradcheckCli, JsonListHasTheSpecKeys) {
  const auto r = runWeft({"gradcheck", kScene, "--json", "--param", "cloths.0.material.density",
                          "--param", "wind.phase", "--eps", "1e-5", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const nlohmann::json list = nlohmann::json::parse(r.out);  // stdout is the JSON document alone
  ASSERT_TRUE(list.is_array());
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0]["param"], "cloths.0.material.density");
  EXPECT_EQ(list[1]["param"], "wind.phase");
  for (const auto& e : list) {
    EXPECT_EQ(e.size(), 5u);
    for (const char* key : {"adjoint", "finite_difference", "relative_error", "error_estimate"})
      EXPECT_TRUE(e[key].is_number()) << key;
    EXPECT_LT(e["relative_error"].get<double>(), 1e-4) << e.dump();
    EXPECT_LT(e["error_estimate"].get<double>(), 1e-6 * std::abs(e["adjoint"].get<double>()))
        << e.dump();
  }
  EXPECT_THAT(r.err, HasSubstr("gradcheck: wind_sysid:"));
  EXPECT_THAT(r.err, HasSubstr("accuracy 0.001 met"));
}

TEST(GradcheckCli, TaskParametersAreTheDefault) {
  const auto r = runWeft({"gradcheck", kScene, "--json", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const nlohmann::json list = nlohmann::json::parse(r.out);
  const nlohmann::json scene = nlohmann::json::parse(test::readFile(kScene));
  ASSERT_EQ(list.size(), scene["task"]["parameters"].size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_EQ(list[i]["param"], scene["task"]["parameters"][i]);
    EXPECT_LT(list[i]["relative_error"].get<double>(), 1e-4) << list[i].dump();
  }
}

struct BadGradcheck {
  const char* name;
  std::vector<std::string> args;
  const char* where;  // "<file>: <path>: " the message must contain
  const char* phrase;
};

TEST(GradcheckCli, BadInputExitsTwoNamingFileAndPath) {
  const std::string noTask = test::dataFile("scenes/hanging_wind.json");
  const BadGradcheck cases[] = {
      {"UnknownParameter",
       {kScene, "--param", "cloths.0.material.nope"},
       "--param cloths.0.material.nope: ",
       "names no value"},
      {"NotDifferentiable",
       {kScene, "--param", "time.dt"},
       "--param time.dt: ",
       "not differentiable"},
      {"NoTask", {noTask}, "task: ", "no task"},
      {"ContactFrictionOfNoObstacle",
       {kScene, "--param", "obstacles.3.friction"},
       "--param obstacles.3.friction: ",
       "names no value"},
      {"BadEps", {kScene, "--eps", "0"}, "--eps: ", "must be in (0, 1)"},
      {"BadBackward", {kScene, "--backward", "cg"}, "--backward: ", "must be one of"},
      {"UnknownSet", {kScene, "--set", "solver.nope.x=1"}, "--set solver.nope.x: ", "unknown path"},
  };
  for (const BadGradcheck& c : cases) {
    SCOPED_TRACE(c.name);
    const auto r = test::expectBadInput("gradcheck", c.args, c.where, c.phrase);
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace weft
