// `weft bench soak`: the judgement of a long run's samples (a leak and a drift are caught, the
// warm-up is not held against the run) and the benchmark run end to end through the CLI.

#include "CliSupport.h"

#include <weft/bench/SoakBench.h>

#include <gtest/gtest.h>

#include <vector>

namespace weft {
namespace {

using bench::judgeSoak;
using bench::SoakWindow;
using test::describe;
using test::readCsv;
using test::runWeft;
using test::TempDir;

// 100 windows of 10 steps: `ms(i)` and `rss(i)` give window i's time per step and memory.
template <class Ms, class Rss>
std::vector<SoakWindow> series(Ms ms, Rss rss) {
  std::vector<SoakWindow> w;
  for (int i = 0; i < 100; ++i) w.push_back({10LL * (i + 1), ms(i), rss(i)});
  return w;
}

TEST(SoakBench, AFlatRunIsSteady) {
  const auto j = judgeSoak(series([](int) { return 10.0; }, [](int) { return 50.0; }));
  EXPECT_DOUBLE_EQ(j.growthMb, 0.0);
  EXPECT_DOUBLE_EQ(j.drift, 1.0);
  EXPECT_FALSE(j.memoryGrew);
  EXPECT_FALSE(j.timeDrifted);
}

TEST(SoakBench, ALeakAfterTheWarmupIsCaught) {
  // 0.1 MB per window: 9 MB over the 90 windows after the warm-up, beyond the 8 MB limit.
  const auto j = judgeSoak(series([](int) { return 10.0; }, [](int i) { return 50.0 + 0.1 * i; }));
  EXPECT_NEAR(j.warmupRssMb, 50.9, 1e-12);
  EXPECT_NEAR(j.growthMb, 9.0, 1e-9);
  EXPECT_TRUE(j.memoryGrew);
  EXPECT_FALSE(j.timeDrifted);
}

TEST(SoakBench, ASlowDriftIsCaught) {
  // From 10 to 15 ms per step. The warm-up is windows 0-9; a tenth of the 90 after it is 9
  // windows: 10-18 (mean index 14) against 91-99 (mean index 95).
  const auto j =
      judgeSoak(series([](int i) { return 10.0 + 5.0 * i / 99.0; }, [](int) { return 50.0; }));
  const double first = 10.0 + 5.0 * 14.0 / 99.0, last = 10.0 + 5.0 * 95.0 / 99.0;
  EXPECT_NEAR(j.drift, last / first, 1e-12);
  EXPECT_TRUE(j.timeDrifted);
  EXPECT_FALSE(j.memoryGrew);
}

TEST(SoakBench, TheWarmupIsNotHeldAgainstTheRun) {
  // The first tenth allocates 100 MB and is a hundred times slower; after it, all is flat.
  const auto j = judgeSoak(series([](int i) { return i < 10 ? 1000.0 : 10.0; },
                                  [](int i) { return i < 10 ? 10.0 * (i + 1) : 100.0; }));
  EXPECT_DOUBLE_EQ(j.growthMb, 0.0);
  EXPECT_DOUBLE_EQ(j.drift, 1.0);
  EXPECT_FALSE(j.memoryGrew || j.timeDrifted);
}

TEST(SoakBench, RunsBothPhasesThroughTheCli) {
  TempDir dir;
  const std::string out = dir.file("soak");
  const auto r = runWeft({"bench", "soak", "--steps", "30", "--evaluations", "5", "--out", out});
  // 0 (steady) or 1 (a limit exceeded: 30 steps of a falling cloth need not be steady).
  ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 1) << describe(r);
  const auto rows = readCsv(out + "/soak.csv");
  ASSERT_EQ(rows.size(), 1u + 30 + 5);  // one window per step and per evaluation
  EXPECT_EQ(rows[1][0], "contact");
  EXPECT_EQ(rows[31][0], "optimiser");
  EXPECT_EQ(rows[30][1], "30");
  EXPECT_EQ(rows[35][1], "5");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(std::stod(rows[i][2]), 0.0) << "ms_per_unit, row " << i;
    EXPECT_GT(std::stod(rows[i][3]), 0.0) << "rss_mb, row " << i;
  }
  const auto summary = readCsv(out + "/soak_summary.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[1][3], "0") << "unconverged contact steps";
  // The exit code is the verdict the phase lines print: 1 exactly when one says it went beyond a
  // limit.
  const bool beyond = r.out.find("(beyond a limit)") != std::string::npos;
  EXPECT_EQ(r.exitCode, beyond ? 1 : 0) << r.out;
  EXPECT_NE(r.out.find("bench soak: contact: 30 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bench soak: optimiser: 5 evaluations"), std::string::npos) << r.out;
}

TEST(SoakBench, ItsOptionsAreRefusedElsewhere) {
  TempDir dir;
  const auto r = runWeft({"bench", "contact", "--steps", "10", "--out", dir.file("c")});
  EXPECT_EQ(r.exitCode, 2) << describe(r);
  EXPECT_NE(r.err.find("--steps"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace weft
