// `weft sweep`: one simulation per combination of --set-grid values, in order (first axis
// slowest), each row the run's summary.json figures; a combination that is bad input is refused
// before anything runs; a run that fails numerically is a row saying so, and the exit code.

#include "CliSupport.h"

#include <support/SceneBuilder.h>

#include <nlohmann/json.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::describe;
using test::readFile;
using test::runWeft;
using test::TempDir;

// RFC 4180 rows: quoted cells may hold commas and doubled quotes.
std::vector<std::vector<std::string>> readQuotedCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : test::splitLines(readFile(path))) {
    std::vector<std::string> cells{""};
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back() += '"', ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        cells.emplace_back();
      } else {
        cells.back() += c;
      }
    }
    rows.push_back(cells);
  }
  return rows;
}

std::map<std::string, std::string> rowAsMap(const std::vector<std::string>& header,
                                            const std::vector<std::string>& row) {
  std::map<std::string, std::string> m;
  for (std::size_t i = 0; i < header.size() && i < row.size(); ++i) m[header[i]] = row[i];
  return m;
}

nlohmann::json sweepScene() {
  nlohmann::json doc = test::hangingClothScene(0.3, 4, 0.01, 12, 400.0);
  return doc;
}

TEST(SweepCli, OneRowPerCombinationWithTheRunsSummaryFigures) {
  TempDir dir;
  const std::string scene = test::writeScene(dir.file("scene.json"), sweepScene());
  const test::ProcessResult r =
      runWeft({"sweep", scene, "--set-grid", "cloths.0.material.stretch=200,800", "--set-grid",
               "gravity=[0,-9.8,0],[0,-1,0],[0,0,0]", "--out", dir.file("sweep"), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, ::testing::HasSubstr("sweep: "));
  EXPECT_THAT(r.out, ::testing::HasSubstr("6 runs, 0 failed"));
  const auto rows = readQuotedCsv(dir.file("sweep/sweep.csv"));
  ASSERT_EQ(rows.size(), 7u);
  const std::vector<std::string>& header = rows[0];
  ASSERT_GE(header.size(), 8u);
  EXPECT_EQ(header[0], "combination");
  EXPECT_EQ(header[1], "cloths.0.material.stretch");
  EXPECT_EQ(header[2], "gravity");
  EXPECT_EQ(header[3], "status");
  // The timing columns come last, so that a distributed sweep's file differs only there.
  EXPECT_EQ(std::vector<std::string>(header.end() - 3, header.end()),
            (std::vector<std::string>{"seconds", "seconds_per_step", "peak_memory_mb"}));
  const char* stretches[] = {"200", "200", "200", "800", "800", "800"};
  const char* gravities[] = {"[0,-9.8,0]", "[0,-1,0]", "[0,0,0]"};
  for (int k = 0; k < 6; ++k) {
    const auto row = rowAsMap(header, rows[k + 1]);
    EXPECT_EQ(row.at("combination"), std::to_string(k));
    EXPECT_EQ(row.at("cloths.0.material.stretch"), stretches[k]);
    EXPECT_EQ(row.at("gravity"), gravities[k % 3]);
    EXPECT_EQ(row.at("status"), "ok");
    EXPECT_EQ(row.at("steps"), "12");
    EXPECT_EQ(row.at("vertices"), "25");
  }
  // Each row is the run `weft simulate` makes with the same values.
  const test::ProcessResult sim =
      runWeft({"simulate", scene, "--set", "cloths.0.material.stretch=800", "--set",
               "gravity=[0,-1,0]", "--out", dir.file("run"), "--quiet"});
  ASSERT_EQ(sim.exitCode, 0) << describe(sim);
  const nlohmann::json summary = nlohmann::json::parse(readFile(dir.file("run/summary.json")));
  const auto row = rowAsMap(header, rows[5]);
  EXPECT_EQ(row.at("pd.iterations_total"), summary["pd"]["iterations_total"].dump());
  EXPECT_EQ(row.at("pd.max_residual"), summary["pd"]["max_residual"].dump());
  // Different gravity, different iterations: the rows are not copies of one run.
  EXPECT_NE(rowAsMap(header, rows[4]).at("pd.max_residual"),
            rowAsMap(header, rows[6]).at("pd.max_residual"));
}

TEST(SweepCli, AFailedRunIsARowAndTheExitCode) {
  TempDir dir;
  const std::string scene = test::writeScene(dir.file("scene.json"), sweepScene());
  const test::ProcessResult r = runWeft({"sweep", scene, "--set-grid",
                                         "cloths.0.initial_velocity=[0,0,0],[1e6,0,0],[0,0.1,0]",
                                         "--out", dir.file("sweep"), "--quiet"});
  EXPECT_EQ(r.exitCode, 3) << describe(r);
  EXPECT_THAT(r.err,
              ::testing::HasSubstr("error: combination 1 (cloths.0.initial_velocity=[1e6,0,0]) "
                                   "on rank 0: numerical failure: step 1: solver: "));
  const auto rows = readQuotedCsv(dir.file("sweep/sweep.csv"));
  ASSERT_EQ(rows.size(), 4u);
  const auto failed = rowAsMap(rows[0], rows[2]);
  EXPECT_THAT(failed.at("status"), ::testing::StartsWith("exit 3: numerical failure: step 1: "));
  EXPECT_EQ(failed.at("steps"), "");
  EXPECT_EQ(rowAsMap(rows[0], rows[1]).at("status"), "ok");
  EXPECT_EQ(rowAsMap(rows[0], rows[3]).at("status"), "ok");
}

TEST(SweepCli, BadCombinationIsRefusedBeforeAnythingRuns) {
  TempDir dir;
  const std::string scene = test::writeScene(dir.file("scene.json"), sweepScene());
  const test::ProcessResult r = test::expectBadInput(
      "sweep",
      {scene, "--set-grid", "cloths.0.material.stretch=100,-5", "--out", dir.file("sweep")},
      "cloths.0.material.stretch", "(combination 1: cloths.0.material.stretch=-5)");
  EXPECT_FALSE(fs::exists(dir.file("sweep")));
  test::expectBadInput("sweep", {scene, "--out", dir.file("sweep")}, "--set-grid",
                       "give at least one");
  test::expectBadInput("sweep", {scene, "--set-grid", "gravity"}, "--set-grid gravity",
                       "expected PATH=VALUE,VALUE");
  test::expectBadInput("sweep", {scene, "--set-grid", "gravity=[0,1,0],,[0,0,0]"},
                       "--set-grid gravity", "empty value");
  test::expectBadInput("sweep", {scene, "--set-grid", "gravity=[0,1,0"}, "--set-grid gravity",
                       "unbalanced");
}

}  // namespace
}  // namespace weft
