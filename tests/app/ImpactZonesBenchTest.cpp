// `weft bench impact_zones` (Liang 2019 Table 1): the table's statistics from given samples, and
// a tiny run end to end through the CLI (8x8 quads, 100 steps: a few dozen zone QPs). No
// wall-clock time is asserted.

#include "CliSupport.h"

#include <weft/bench/ImpactZonesBench.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace weft {
namespace {

using bench::meanSd;
using bench::summariseZones;
using bench::ZoneBackwardSample;
using test::describe;
using test::readCsv;
using test::runWeft;
using test::TempDir;

TEST(ImpactZonesBench, MeanAndSampleStandardDeviation) {
  const bench::MeanSd v = meanSd({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(v.mean, 2.5);
  EXPECT_NEAR(v.sd, std::sqrt(5.0 / 3.0), 1e-15);
  EXPECT_DOUBLE_EQ(meanSd({7.0}).sd, 0.0);
  EXPECT_DOUBLE_EQ(meanSd({}).mean, 0.0);
}

TEST(ImpactZonesBench, SummaryCountsSingularZonesAndComparesOnlyTheOthers) {
  auto sample = [](int n, int m, int active, int rank, double kkt, double qr, bool ok,
                   double diff) {
    ZoneBackwardSample s;
    s.n = n, s.m = m, s.active = active, s.rank = rank;
    s.kktSeconds = kkt, s.qrSeconds = qr, s.kktOk = ok;
    s.differenceDx = s.differenceAll = diff;
    return s;
  };
  // Sizes n + m: 12, 24, 36; ranks 1, 2, 3. The singular zone's difference is not counted.
  std::vector<ZoneBackwardSample> samples = {sample(9, 3, 1, 1, 2.0, 1.0, true, 1e-12),
                                             sample(18, 6, 3, 2, 4.0, 1.0, false, 1.0),
                                             sample(27, 9, 3, 3, 6.0, 1.0, true, 1e-10)};
  samples[1].tightWithoutMultiplier = 2;
  const bench::ImpactZonesSummary s = summariseZones(samples);
  EXPECT_EQ(s.zones, 3);
  EXPECT_EQ(s.kktSingular, 1);
  EXPECT_EQ(s.degenerate, 1);
  EXPECT_EQ(s.rankDeficient, 1);
  EXPECT_EQ(s.withoutActive, 0);
  EXPECT_DOUBLE_EQ(s.kktSize.mean, 24.0);
  EXPECT_DOUBLE_EQ(s.kktSize.sd, 12.0);
  EXPECT_DOUBLE_EQ(s.qrSize.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.sizeRatio, 12.0);
  EXPECT_DOUBLE_EQ(s.speedup, 4.0);  // ratio of the means
  EXPECT_DOUBLE_EQ(s.medianSpeedup, 4.0);
  EXPECT_DOUBLE_EQ(s.maxDifferenceDx, 1e-10);
}

TEST(ImpactZonesBench, ATinyRunWritesBothTables) {
  TempDir dir;
  const std::string out = dir.file("bench");
  const auto r = runWeft(
      {"bench", "impact_zones", "--quick", "--resolutions", "8", "--steps", "100", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto table = readCsv(out + "/impact_zones.csv");
  ASSERT_EQ(table.size(), 2u);  // header, 8x8
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < table[0].size(); ++i)
      if (table[0][i] == name) return table[1][i];
    ADD_FAILURE() << "no column " << name;
    return std::string();
  };
  EXPECT_EQ(column("quads"), "8");
  EXPECT_EQ(column("steps"), "100");
  EXPECT_EQ(column("failed_step"), "0");
  const int zoneQps = std::stoi(column("zone_qps"));
  EXPECT_GT(zoneQps, 0) << "the cloth should fold onto itself within 100 steps";
  // Mean ± standard deviation cells.
  EXPECT_NE(column("kkt_size").find(" ± "), std::string::npos);
  const auto zones = readCsv(out + "/zones.csv");
  ASSERT_EQ(zones.size(), 1u + static_cast<std::size_t>(zoneQps));
  int singular = 0;
  for (std::size_t k = 1; k < zones.size(); ++k) {
    const int n = std::stoi(zones[k][2]), m = std::stoi(zones[k][3]);
    const int active = std::stoi(zones[k][4]), rank = std::stoi(zones[k][5]);
    EXPECT_EQ(std::stoi(zones[k][6]), n + m) << "zone " << k;
    EXPECT_EQ(n % 3, 0);
    EXPECT_LE(rank, active);
    EXPECT_LE(active, m);
    if (zones[k][9] == "1")
      EXPECT_LT(std::stod(zones[k][10]), 1e-6) << "QR and KKT disagree on zone " << k;
    else
      ++singular;
  }
  EXPECT_EQ(std::to_string(singular), column("kkt_singular"));
}

}  // namespace
}  // namespace weft
