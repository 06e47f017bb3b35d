// `weft gradient` through the real binary: the table and the --json list, the gradient against
// gradcheck's direct-LU adjoint on the same forward run within the estimate it prints, a missed
// accuracy warned about, and bad input.

#include <app/CliSupport.h>

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
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kScene = std::string(WEFT_ASSET_DIR) + "/scenes/wind_sysid.json";
const std::vector<std::string> kParams = {
    "--param", "cloths.0.material.stretch", "--param", "wind.strength", "--param", "wind.phase"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(GradientCli, PrintsEachComponentWithItsErrorEstimateAndASummary) {
  const auto r = runWeft(with({"gradient", kScene, "--threads", "1"}, kParams));
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  for (int i = 0; i < 3; ++i) {
    std::istringstream in(lines[i]);
    std::string param, k1, k2;
    double gradient = 0, estimate = -1;
    in >> param >> k1 >> gradient >> k2 >> estimate;
    EXPECT_EQ(param, kParams[2 * i + 1]);
    EXPECT_EQ(k1, "gradient");
    EXPECT_EQ(k2, "error_estimate");
    EXPECT_NE(gradient, 0.0);
    EXPECT_GE(estimate, 0.0);
    EXPECT_LE(estimate, 1e-3 * std::abs(gradient) * 10) << lines[i];
  }
  EXPECT_THAT(lines[3], StartsWith("gradient: wind_sysid: 3 parameters"));
  EXPECT_THAT(lines[3], HasSubstr("accuracy 0.001 met"));
}

TEST(GradientCli, EqualsGradchecksDirectAdjointWithinItsEstimate) {
  // The same forward run as gradcheck's (Newton to 1e-8 m/s^2), the scene's own backward
  // settings (GMRES from 1e-4, error-controlled to 1e-3).
  const auto g =
      runWeft(with({"gradient", kScene, "--json", "--threads", "1", "--set", "solver.method=newton",
                    "--set", "solver.pd_tolerance=1e-8", "--set", "solver.pd_iterations=20000"},
                   kParams));
  ASSERT_EQ(g.exitCode, 0) << describe(g);
  const auto c = runWeft(
      with({"gradcheck", kScene, "--json", "--threads", "1", "--backward", "direct"}, kParams));
  ASSERT_EQ(c.exitCode, 0) << describe(c);
  const nlohmann::json gradient = nlohmann::json::parse(g.out);
  const nlohmann::json check = nlohmann::json::parse(c.out);
  ASSERT_EQ(gradient.size(), 3u);
  ASSERT_EQ(check.size(), 3u);
  double norm = 0.0;
  for (const auto& e : check) norm += std::pow(e["adjoint"].get<double>(), 2);
  norm = std::sqrt(norm);
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& e = gradient[i];
    EXPECT_EQ(e.size(), 4u) << e.dump();
    EXPECT_EQ(e["param"], check[i]["param"]);
    EXPECT_TRUE(e["parameter_value"].is_number());
    const double value = e["value"].get<double>(), estimate = e["error_estimate"].get<double>();
    const double direct = check[i]["adjoint"].get<double>();
    // Within the estimate, allowing the direct LU its round-off.
    EXPECT_LE(std::abs(value - direct), estimate + 1e-12 * norm) << e.dump() << " vs " << direct;
    EXPECT_NE(value, direct) << "an iterative gradient, not the direct one";
  }
  EXPECT_THAT(g.err, HasSubstr("gradient: wind_sysid: 3 parameters"));
}

TEST(GradientCli, AnAccuracyThatCannotBeMetIsWarnedAbout) {
  const auto r = runWeft(with(
      {"gradient", kScene, "--threads", "1", "--set", "solver.backward.accuracy=1e-300"}, kParams));
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("MISSED"));
  EXPECT_THAT(r.err, HasSubstr("warning: backward: the gradient's estimated relative error"));
}

TEST(GradientCli, BadInputExitsTwoNamingFileAndPath) {
  const std::string noTask = test::dataFile("scenes/hanging_wind.json");
  auto r = test::expectBadInput("gradient", {noTask}, "task: ", "no task");
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = test::expectBadInput("gradient", {kScene, "--param", "time.dt"},
                           "--param time.dt: ", "not differentiable");
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = test::expectBadInput("gradient", {kScene, "--set", "solver.backward.accuracy=2"},
                           "--set solver.backward.accuracy: ", "");
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
}  // namespace weft
