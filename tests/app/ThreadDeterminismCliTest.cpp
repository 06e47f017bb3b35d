// A run does not depend on the number of threads: `weft simulate` with one and with two OpenMP
// threads writes bit-identical positions and the same per-step statistics apart from the
// timings, on two contact scenes with self-collision (the parallel loops: element projections,
// contact detection, self-collision boxes, the contact solve's groups). Three of those loops are
// sum reductions whose rounding depends on the thread count (the stretch and bending energies,
// the self-collision boxes' mean extent, which sets the hash grid's cell size); this test is what
// shows whether that reaches a result (docs/hardening.md).

#include "CliSupport.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace weft {
namespace {

using test::describe;
using test::readCsv;
using test::readFile;
using test::runWeft;
using test::TempDir;

class ThreadDeterminism : public ::testing::TestWithParam<std::string> {};

TEST_P(ThreadDeterminism, OneAndTwoThreadsGiveBitIdenticalRuns) {
  // 45 steps: the Sphere's cloth lands at step 26, Crumple's at step 35.
  TempDir dir;
  const std::string scene = std::string(WEFT_ASSET_DIR) + "/scenes/" + GetParam() + ".json";
  std::vector<std::string> outs;
  for (const char* threads : {"1", "2"}) {
    outs.push_back(dir.file(std::string("t") + threads));
    const auto r = runWeft({"simulate", scene, "--steps", "45", "--threads", threads, "--quiet",
                            "--out", outs.back()});
    ASSERT_EQ(r.exitCode, 0) << describe(r);
  }
  const std::string a = readFile(outs[0] + "/positions.npy"),
                    b = readFile(outs[1] + "/positions.npy");
  ASSERT_GT(a.size(), 128u);
  EXPECT_TRUE(a == b) << "positions.npy differs between 1 and 2 threads";
  // stats.csv: every column but the timings (seconds_*).
  const auto s1 = readCsv(outs[0] + "/stats.csv"), s2 = readCsv(outs[1] + "/stats.csv");
  ASSERT_EQ(s1.size(), s2.size());
  ASSERT_EQ(s1.size(), 46u);
  const std::vector<std::string>& header = s1[0];
  int contacts = 0;
  for (std::size_t row = 1; row < s1.size(); ++row) {
    ASSERT_EQ(s1[row].size(), header.size());
    ASSERT_EQ(s2[row].size(), header.size());
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c].rfind("seconds", 0) == 0) continue;
      EXPECT_EQ(s1[row][c], s2[row][c]) << header[c] << ", step " << row;
      if (header[c] == "contacts_stick" || header[c] == "contacts_slip")
        contacts += std::stoi(s1[row][c]);
    }
  }
  EXPECT_GT(contacts, 0) << "the run never reached contact";
}

INSTANTIATE_TEST_SUITE_P(ContactScenes, ThreadDeterminism, ::testing::Values("sphere", "crumple"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace weft
