// `weft bench distribution`: the list-scheduling projection against hand-computed makespans,
// and the benchmark's files from a small store of runs.

#include "CliSupport.h"

#include <weft/bench/DistributionBench.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using test::TempDir;

TEST(DistributionBench, ListSchedulingHandsEachItemToTheFirstFreeRank) {
  using bench::listScheduleSeconds;
  EXPECT_DOUBLE_EQ(listScheduleSeconds({}, 4, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(listScheduleSeconds({3, 1, 2}, 1, 0.0), 6.0);
  // Two ranks: 3 | 1, then 2 goes to the rank free at 1 -> 3; makespan 3.
  EXPECT_DOUBLE_EQ(listScheduleSeconds({3, 1, 2}, 2, 0.0), 3.0);
  // In order, not sorted: a long item last sets the makespan.
  EXPECT_DOUBLE_EQ(listScheduleSeconds({1, 1, 1, 1, 10}, 2, 0.0), 12.0);
  // More ranks than items: the longest item.
  EXPECT_DOUBLE_EQ(listScheduleSeconds({5, 2, 7}, 8, 0.0), 7.0);
  // Hand-out cost per item.
  EXPECT_DOUBLE_EQ(listScheduleSeconds({1, 1}, 1, 0.5), 3.0);
}

TEST(DistributionBench, WritesTheHandOutTableAndTheProjectionFromAStore) {
  TempDir dir;
  fs::create_directories(dir.file("runs"));
  // Four runs of 100 s and one of 1000 s, as a comparison stores them (wall_s is column 6).
  const char* runs[][2] = {{"wind_sysid_lbfgsb_1.csv", "100"},
                           {"wind_sysid_cmaes_1.csv", "100"},
                           {"wind_sysid_es1p1_1.csv", "100"},
                           {"flag_lbfgsb_1.csv", "100"},
                           {"flag_cmaes_1.csv", "1000"}};
  const char* rows[] = {"wind_sysid,lbfgsb,1,1,60,100,0.5\n", "wind_sysid,cmaes,1,1,30,100,0.5\n",
                        "wind_sysid,es1p1,1,1,30,100,0.5\n", "flag,lbfgsb,1,1,200,100,0.5\n",
                        "flag,cmaes,1,1,100,1000,0.5\n"};
  for (int k = 0; k < 5; ++k) {
    std::ofstream f(dir.file(std::string("runs/") + runs[k][0]));
    f << "task,method,seed,evaluation,steps,wall_s,loss\n" << rows[k];
  }
  const test::ProcessResult r =
      runWeft({"bench", "distribution", "--quick", "--store", dir.file("runs"), "--serial-seconds",
               "10", "--out", dir.file("out")});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, ::testing::HasSubstr("bench distribution: serial, "));
  const auto handout = test::readCsv(dir.file("out/distribution.csv"));
  ASSERT_EQ(handout.size(), 5u);  // header, empty items, three spinning item lengths
  EXPECT_EQ(handout[1][0], "serial");
  for (std::size_t k = 2; k < 5; ++k) {
    const double efficiency = std::stod(handout[k][5]);
    EXPECT_GT(efficiency, 0.5) << "a serial map costs more than the work it runs";
    EXPECT_LE(efficiency, 1.0 + 1e-9);
  }
  const auto projection = test::readCsv(dir.file("out/projection.csv"));
  ASSERT_EQ(projection.size(), 6u);  // 1, 2, 8, 32, 128 ranks
  // Task order (wind_sysid before flag in the task table), then seed, then method: on 1 rank
  // 1400 s + 10 s; on 2 ranks the four 100 s runs take two rounds and the 1000 s flag CMA-ES
  // run starts at 200 s -> 1200 + 10.
  EXPECT_NEAR(std::stod(projection[1][1]), 1410.0, 1.0);
  EXPECT_NEAR(std::stod(projection[2][1]), 1210.0, 1.0);
  EXPECT_NEAR(std::stod(projection[5][1]), 1010.0, 1.0);
  EXPECT_EQ(projection[5][5], "longest run");
}

}  // namespace
}  // namespace weft
