// The distributing commands under `mpirun -np 2` give the serial run's results: `weft sweep`'s
// file apart from its timing columns, `weft landscape`'s file byte for byte, `weft optimize`'s
// CMA-ES and (1+1)-ES logs entry for entry, `weft bench applications`' stored runs; a failed item
// is reported with its rank; a rank killed mid-comparison leaves a store that --resume finishes
// with the serial runs. Built only with MPI (WEFT_MPIEXEC).

#include "CliSupport.h"

#include <support/SceneBuilder.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <dirent.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

namespace fs = std::filesystem;

namespace weft {
namespace {

using test::describe;
using test::readFile;
using test::runWeft;
using test::TempDir;

std::vector<std::string> mpirunArgv(int ranks, const std::vector<std::string>& weftArgs) {
  std::vector<std::string> argv{WEFT_MPIEXEC, "-np", std::to_string(ranks)};
#ifdef WEFT_MPIEXEC_OPEN_MPI
  argv.push_back("--oversubscribe");
  if (::geteuid() == 0) argv.push_back("--allow-run-as-root");
#endif
  argv.push_back(WEFT_BINARY);
  argv.insert(argv.end(), weftArgs.begin(), weftArgs.end());
  return argv;
}

test::ProcessResult mpirunWeft(int ranks, const std::vector<std::string>& args) {
  return test::runProcess(mpirunArgv(ranks, args));
}

std::string asset(const std::string& name) {
  return std::string(WEFT_ASSET_DIR) + "/" + name;
}

// The file's lines with the given comma-separated columns dropped (timings).
std::vector<std::string> withoutColumns(const std::string& path, std::vector<std::size_t> drop) {
  std::vector<std::string> lines;
  for (const std::string& line : test::splitLines(readFile(path))) {
    const std::vector<std::string> cells = test::splitCommas(line);
    std::string kept;
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (std::find(drop.begin(), drop.end(), i) == drop.end()) kept += cells[i] + ",";
    lines.push_back(kept);
  }
  return lines;
}

// Runs `args` once serially into dir/serial and once under mpirun into dir/mpi (--out appended);
// both must succeed. Returns the mpirun run.
test::ProcessResult runSerialThenMpi(const std::vector<std::string>& args, const TempDir& dir,
                                     int ranks = 3) {
  auto serialArgs = args, mpiArgs = args;
  serialArgs.insert(serialArgs.end(), {"--out", dir.file("serial")});
  mpiArgs.insert(mpiArgs.end(), {"--out", dir.file("mpi")});
  const test::ProcessResult serial = runWeft(serialArgs);
  EXPECT_EQ(serial.exitCode, 0) << describe(serial);
  const test::ProcessResult mpi = mpirunWeft(ranks, mpiArgs);
  EXPECT_EQ(mpi.exitCode, 0) << describe(mpi);
  return mpi;
}

TEST(DistributedCli, SweepWritesTheSerialFileApartFromItsTimingColumns) {
  TempDir dir;
  const std::string scene =
      test::writeScene(dir.file("scene.json"), test::hangingClothScene(0.3, 4, 0.01, 20, 400.0));
  const std::vector<std::string> args{"sweep",      scene,
                                      "--set-grid", "cloths.0.material.stretch=100,300,900",
                                      "--set-grid", "cloths.0.material.bend=0,0.001",
                                      "--quiet"};
  const test::ProcessResult mpi = runSerialThenMpi(args, dir);
  ASSERT_EQ(mpi.exitCode, 0);
  EXPECT_THAT(mpi.out, ::testing::HasSubstr("6 runs, 0 failed"));
  EXPECT_THAT(mpi.out, ::testing::HasSubstr("MPI, 3 ranks"));
  const auto header =
      test::splitCommas(test::splitLines(readFile(dir.file("serial/sweep.csv")))[0]);
  const std::size_t n = header.size();
  ASSERT_EQ(header[n - 3], "seconds");
  EXPECT_EQ(withoutColumns(dir.file("serial/sweep.csv"), {n - 3, n - 2, n - 1}),
            withoutColumns(dir.file("mpi/sweep.csv"), {n - 3, n - 2, n - 1}));
}

TEST(DistributedCli, AFailedItemIsReportedWithItsRankAndTheOthersAreKept) {
  TempDir dir;
  const std::string scene =
      test::writeScene(dir.file("scene.json"), test::hangingClothScene(0.3, 4, 0.01, 10, 400.0));
  const test::ProcessResult r =
      mpirunWeft(2, {"sweep", scene, "--set-grid",
                     "cloths.0.initial_velocity=[0,0,0],[1e6,0,0],[0,0.1,0],[0,0,0.1]", "--out",
                     dir.file("sweep"), "--quiet"});
  EXPECT_EQ(r.exitCode, 3) << describe(r);
  EXPECT_THAT(r.err, ::testing::ContainsRegex("error: combination 1 \\(cloths.0.initial_velocity="
                                              "\\[1e6,0,0\\]\\) on rank [01]: numerical failure"));
  const auto lines = test::splitLines(readFile(dir.file("sweep/sweep.csv")));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_THAT(lines[1], ::testing::HasSubstr(",ok,"));
  EXPECT_THAT(lines[2], ::testing::HasSubstr("exit 3: numerical failure"));
  EXPECT_THAT(lines[3], ::testing::HasSubstr(",ok,"));
  EXPECT_THAT(lines[4], ::testing::HasSubstr(",ok,"));
}

TEST(DistributedCli, LandscapeIsTheSerialFileByteForByte) {
  TempDir dir;
  const std::vector<std::string> args{"landscape", asset("scenes/wind_sysid.json"),
                                      "--param",   "cloths.0.material.stretch",
                                      "--param",   "wind.strength",
                                      "--grid",    "3",
                                      "--quiet",   "--threads",
                                      "1"};
  ASSERT_EQ(runSerialThenMpi(args, dir).exitCode, 0);
  EXPECT_EQ(readFile(dir.file("serial/landscape.csv")), readFile(dir.file("mpi/landscape.csv")));
  EXPECT_EQ(test::splitLines(readFile(dir.file("mpi/landscape.csv"))).size(), 10u);
}

TEST(DistributedCli, GradientFreeOptimisersLogTheSerialRun) {
  for (const char* method : {"cmaes", "es1p1"}) {
    TempDir dir;
    const std::vector<std::string> args{"optimize", asset("scenes/wind_sysid.json"),
                                        "--method", method,
                                        "--budget", "900",
                                        "--seed",   "4",
                                        "--quiet",  "--threads",
                                        "1"};
    auto serialArgs = args, mpiArgs = args;
    serialArgs.insert(serialArgs.end(), {"--out", dir.file("serial")});
    mpiArgs.insert(mpiArgs.end(), {"--out", dir.file("mpi")});
    const test::ProcessResult serial = runWeft(serialArgs);
    ASSERT_EQ(serial.exitCode, 0) << describe(serial);
    for (int ranks : {2, 3}) {
      const test::ProcessResult mpi = mpirunWeft(ranks, mpiArgs);
      ASSERT_EQ(mpi.exitCode, 0) << method << " on " << ranks << " ranks: " << describe(mpi);
      // loss.csv: evaluation,steps,wall_s,loss,parameters...; wall_s is a timing.
      const auto s = withoutColumns(dir.file("serial/loss.csv"), {2});
      EXPECT_EQ(s, withoutColumns(dir.file("mpi/loss.csv"), {2})) << method << ", " << ranks;
      EXPECT_EQ(s.size(), 31u) << method;  // header + 900 / 30 evaluations
      const auto result = nlohmann::json::parse(readFile(dir.file("mpi/result.json")));
      EXPECT_EQ(result["processes"], "MPI, " + std::to_string(ranks) + " ranks");
      fs::remove_all(dir.file("mpi"));
    }
  }
}

TEST(DistributedCli, QuickApplicationsOnThreeRanksStoreTheSerialRuns) {
  TempDir dir;
  const test::ProcessResult mpi =
      runSerialThenMpi({"bench", "applications", "--quick", "--tasks", "napkin_4x4,wind_sysid",
                        "--seeds", "2", "--budget", "1200", "--threads", "1"},
                       dir);
  ASSERT_EQ(mpi.exitCode, 0);
  EXPECT_THAT(mpi.out, ::testing::HasSubstr("12 run(s) made, 0 resumed"));
  int compared = 0;
  for (const auto& e : fs::directory_iterator(dir.file("serial/runs"))) {
    if (e.path().extension() != ".csv") continue;
    const std::string name = e.path().filename().string();
    // task,method,seed,evaluation,steps,wall_s,loss: all but the wall seconds.
    EXPECT_EQ(withoutColumns(e.path(), {5}), withoutColumns(dir.file("mpi/runs/" + name), {5}))
        << name;
    EXPECT_EQ(readFile(dir.file("serial/runs/parameters/" + name)),
              readFile(dir.file("mpi/runs/parameters/" + name)))
        << name;
    ++compared;
  }
  EXPECT_EQ(compared, 12);
  EXPECT_FALSE(fs::exists(dir.file("mpi.partial"))) << "the store is removed once tabulated";
}

TEST(DistributedCli, GradientMethodsRunOnRankZeroAloneAndSaySo) {
  TempDir dir;
  const test::ProcessResult r =
      mpirunWeft(2, {"optimize", asset("scenes/wind_sysid.json"), "--method", "lbfgsb", "--budget",
                     "240", "--quiet", "--threads", "1", "--out", dir.file("o")});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.err, ::testing::HasSubstr("note: lbfgsb evaluates one point at a time: rank 0 "
                                          "runs it alone"));
  EXPECT_TRUE(fs::exists(dir.file("o/result.json")));
}

// The pids of `parent`'s children (mpirun's ranks on this machine).
std::vector<pid_t> childrenOf(pid_t parent) {
  std::vector<pid_t> children;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent) children.push_back(std::stoi(name));
  }
  return children;
}

// The rank a process was started as (its OMPI_COMM_WORLD_RANK), or -1.
int rankOf(pid_t pid) {
  std::ifstream env("/proc/" + std::to_string(pid) + "/environ");
  std::string var;
  while (std::getline(env, var, '\0'))
    if (var.rfind("OMPI_COMM_WORLD_RANK=", 0) == 0) return std::atoi(var.c_str() + 21);
  return -1;
}

int storedRuns(const std::string& store) {
  int n = 0;
  if (fs::is_directory(store))
    for (const auto& e : fs::directory_iterator(store)) n += e.path().extension() == ".csv";
  return n;
}

TEST(DistributedCli, ApplicationsKilledRankLeavesAStoreThatResumeFinishesWithTheSerialRuns) {
  TempDir dir;
  const std::vector<std::string> bench{"bench", "applications", "--tasks", "wind_sysid", "--seeds",
                                       "3",     "--budget",     "1500",    "--threads",  "1"};
  auto serialArgs = bench;
  serialArgs.insert(serialArgs.end(), {"--out", dir.file("serial")});
  const test::ProcessResult serial = runWeft(serialArgs);
  ASSERT_EQ(serial.exitCode, 0) << describe(serial);

  // Under mpirun: kill rank 1 once the first runs are stored.
  auto mpiArgs = bench;
  mpiArgs.insert(mpiArgs.end(), {"--out", dir.file("mpi")});
  const std::vector<std::string> argv = mpirunArgv(2, mpiArgs);
  std::vector<char*> cargv;
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  const std::string log = dir.file("mpirun.log");
  const pid_t mpirun = ::fork();
  ASSERT_GE(mpirun, 0);
  if (mpirun == 0) {
    FILE* f = std::freopen(log.c_str(), "w", stderr);
    (void)f;
    ::execv(cargv[0], cargv.data());
    ::_exit(127);
  }
  const std::string store = dir.file("mpi.partial");
  bool killed = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!killed && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(mpirun, &status, WNOHANG) == mpirun) break;  // finished before the kill
    if (storedRuns(store) >= 2)
      for (pid_t child : childrenOf(mpirun))
        if (rankOf(child) == 1) killed = ::kill(child, SIGKILL) == 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  int status = 0;
  ::waitpid(mpirun, &status, 0);
  ASSERT_TRUE(killed) << "the comparison ended before a rank could be killed: " << readFile(log);
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(log);
  const int kept = storedRuns(store);
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 9) << "every run was made before the kill";
  EXPECT_FALSE(fs::exists(dir.file("mpi/applications.csv")));
  // Every stored run is whole: its rows parse and it has its parameter file.
  for (const auto& e : fs::directory_iterator(store)) {
    if (e.path().extension() != ".csv") continue;
    const auto lines = test::splitLines(readFile(e.path()));
    ASSERT_GE(lines.size(), 2u) << e.path();
    EXPECT_TRUE(fs::exists(fs::path(store) / "parameters" / e.path().filename())) << e.path();
  }

  auto resumeArgs = mpiArgs;
  resumeArgs.push_back("--resume");
  const test::ProcessResult resumed = mpirunWeft(2, resumeArgs);
  ASSERT_EQ(resumed.exitCode, 0) << describe(resumed);
  EXPECT_THAT(resumed.out, ::testing::HasSubstr(std::to_string(9 - kept) + " run(s) made, " +
                                                std::to_string(kept) + " resumed"));
  for (const auto& e : fs::directory_iterator(dir.file("serial/runs"))) {
    if (e.path().extension() != ".csv") continue;
    const std::string mine = dir.file("mpi/runs/" + e.path().filename().string());
    // task,method,seed,evaluation,steps,wall_s,loss: all but the wall seconds.
    EXPECT_EQ(withoutColumns(e.path(), {5}), withoutColumns(mine, {5})) << e.path().filename();
  }
}

TEST(DistributedCli, VerbsThatDoNotDistributeRunOnceOnRankZero) {
  TempDir dir;
  const std::string scene =
      test::writeScene(dir.file("scene.json"), test::hangingClothScene(0.3, 4, 0.01, 5, 400.0));
  const test::ProcessResult r =
      mpirunWeft(2, {"simulate", scene, "--out", dir.file("run"), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_EQ(test::splitLines(r.out).size(), 1u) << r.out;  // one "simulate: ..." line
  EXPECT_TRUE(fs::exists(dir.file("run/summary.json")));
}

TEST(DistributedCli, BadInputIsReportedOnceAndExitsTwo) {
  TempDir dir;
  const test::ProcessResult r = mpirunWeft(2, {"sweep", dir.file("missing.json"), "--set-grid",
                                               "gravity=[0,0,0]", "--out", dir.file("s")});
  EXPECT_EQ(r.exitCode, 2) << describe(r);
  std::size_t errors = 0;
  for (std::size_t at = r.err.find("error: "); at != std::string::npos;
       at = r.err.find("error: ", at + 1))
    ++errors;
  EXPECT_EQ(errors, 1u) << r.err;
}

}  // namespace
}  // namespace weft
