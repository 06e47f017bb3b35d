// The MPI WorkDistributor, run by ctest under `mpirun -np 2` (and -np 3): every rank runs these
// tests in the same order, so their map() and rootFirst() calls meet. Each item runs once, on
// some rank, both ranks take items, every rank gets every result in item order, failures keep
// their rank and kind, and rootFirst's step runs on rank 0 before the others read what it made.

#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>

#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

namespace weft {
namespace {

long long sumOverRanks(long long local) {
  long long total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

TEST(MpiDistributor, IsTheLaunchersRanks) {
  WorkDistributor& workers = processWorkers();
  int size = 0, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  ASSERT_GE(size, 2) << "run this test under mpirun -np 2 or more";
  EXPECT_EQ(workers.size(), size);
  EXPECT_EQ(workers.rank(), rank);
  EXPECT_EQ(launchRank(), rank);
  EXPECT_EQ(workers.description(), "MPI, " + std::to_string(size) + " ranks");
}

TEST(MpiDistributor, EachItemRunsOnceSomewhereAndEveryRankGetsEveryResult) {
  WorkDistributor& workers = processWorkers();
  long long ranHere = 0;
  const std::size_t count = 60;
  const auto results = workers.map(count, [&](std::size_t i) {
    ++ranHere;
    std::this_thread::sleep_for(std::chrono::milliseconds(3));  // long enough to share out
    return std::to_string(i * i) + "@" + std::to_string(workers.rank());
  });
  EXPECT_EQ(sumOverRanks(ranHere), static_cast<long long>(count));
  ASSERT_EQ(results.size(), count);
  std::set<int> ranks;
  for (std::size_t i = 0; i < count; ++i) {
    ASSERT_TRUE(results[i].ok) << i;
    EXPECT_EQ(results[i].data, std::to_string(i * i) + "@" + std::to_string(results[i].rank));
    ranks.insert(results[i].rank);
  }
  EXPECT_EQ(static_cast<int>(ranks.size()), workers.size()) << "some rank took no item";
  // Every rank holds the same results: compare a checksum.
  // (Unsigned: the hash wraps, which is defined for unsigned types only.)
  unsigned long long checksum = 0;
  for (const WorkItemResult& r : results)
    for (char c : r.data) checksum = checksum * 31 + static_cast<unsigned char>(c);
  unsigned long long lo = 0, hi = 0;
  MPI_Allreduce(&checksum, &lo, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&checksum, &hi, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(lo, hi);
}

TEST(MpiDistributor, FewerItemsThanRanksAndNone) {
  WorkDistributor& workers = processWorkers();
  EXPECT_TRUE(workers.map(0, [](std::size_t) { return std::string("x"); }).empty());
  const auto one = workers.map(1, [](std::size_t) { return std::string("only"); });
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].data, "only");
}

TEST(MpiDistributor, FailuresKeepTheirRankAndKind) {
  WorkDistributor& workers = processWorkers();
  const auto results = workers.map(12, [&](std::size_t i) -> std::string {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (i == 4) throw InputError("s.json", "gravity", "must be finite");
    if (i == 9) throw NumericalError(3, "contact_solve", "force is not finite");
    return std::to_string(workers.rank());
  });
  for (std::size_t i = 0; i < results.size(); ++i) EXPECT_EQ(results[i].ok, i != 4 && i != 9) << i;
  EXPECT_EQ(results[4].exitCode, 2);
  EXPECT_EQ(results[9].exitCode, 3);
  EXPECT_EQ(results[9].message, "numerical failure: step 3: contact_solve: force is not finite");
  EXPECT_GE(results[4].rank, 0);
  EXPECT_LT(results[4].rank, workers.size());
  EXPECT_THROW(rethrowFailure(results[4]), InputError);
  try {
    rethrowFailure(results[9]);
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.module(), "contact_solve");
  }
}

TEST(MpiDistributor, RootFirstRunsOnRankZeroBeforeTheOthers) {
  WorkDistributor& workers = processWorkers();
  // The ranks share a parent (mpirun), so a path from its pid is the same on every rank.
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("weft-rootfirst-" + std::to_string(getppid()) + ".txt");
  std::string seen;
  workers.rootFirst([&] {
    if (workers.isRoot()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the others would race
      std::ofstream(file) << "made by rank 0";
    } else {
      std::ifstream in(file);
      std::getline(in, seen);
    }
  });
  if (!workers.isRoot()) {
    EXPECT_EQ(seen, "made by rank 0");
  }
  workers.map(0, [](std::size_t) { return std::string(); });  // everyone has read it
  if (workers.isRoot()) std::filesystem::remove(file);

  // A failure on rank 0 leaves rank 0 with the error and the others with a quiet exit code.
  if (workers.isRoot()) {
    EXPECT_THROW(workers.rootFirst([] { throw InputError("store", "--resume", "is not empty"); }),
                 InputError);
  } else {
    try {
      workers.rootFirst([] { ADD_FAILURE() << "the step ran after rank 0 failed"; });
      ADD_FAILURE() << "no QuietExit";
    } catch (const QuietExit& e) {
      EXPECT_EQ(e.code, 2);
    }
  }
}

}  // namespace
}  // namespace weft

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int failed = RUN_ALL_TESTS();
  // A failure on any rank fails the test (mpirun reports a non-zero exit).
  weft::endProcessWorkers(0, true);
  return failed;
}
