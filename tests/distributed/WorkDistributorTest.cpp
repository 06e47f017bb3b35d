// The serial WorkDistributor and what every distributor shares: each item once, results in item
// order, a failing item captured with the CLI's exit code and message (not thrown), and
// rethrowFailure giving back the error as it was thrown.

#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>

namespace weft {
namespace {

TEST(SerialDistributor, RunsEachItemOnceInOrder) {
  const auto workers = makeSerialDistributor();
  EXPECT_EQ(workers->rank(), 0);
  EXPECT_EQ(workers->size(), 1);
  EXPECT_EQ(workers->description(), "serial");
  std::vector<std::size_t> order;
  const auto results = workers->map(5, [&](std::size_t i) {
    order.push_back(i);
    return std::string(i, 'x');
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  ASSERT_EQ(results.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_TRUE(results[i].ok);
    EXPECT_EQ(results[i].data, std::string(i, 'x'));
    EXPECT_EQ(results[i].rank, 0);
  }
  EXPECT_EQ(firstFailure(results), nullptr);
  EXPECT_TRUE(workers->map(0, [](std::size_t) { return std::string("never"); }).empty());
}

TEST(SerialDistributor, FailuresAreResultsWithTheClisExitCodesAndTheOtherItemsStillRun) {
  const auto workers = makeSerialDistributor();
  int ran = 0;
  const auto results = workers->map(5, [&](std::size_t i) -> std::string {
    ++ran;
    if (i == 1) throw InputError("scene.json", "cloths.0.mesh", "cannot read");
    if (i == 2) throw NumericalError(7, "solver", "residual is not finite");
    if (i == 3) throw std::logic_error("broken invariant");
    return "fine";
  });
  EXPECT_EQ(ran, 5);
  EXPECT_TRUE(results[0].ok);
  EXPECT_TRUE(results[4].ok);
  EXPECT_FALSE(results[1].ok);
  EXPECT_EQ(results[1].exitCode, 2);
  EXPECT_EQ(results[1].message, "scene.json: cloths.0.mesh: cannot read");
  EXPECT_EQ(results[2].exitCode, 3);
  EXPECT_EQ(results[2].message, "numerical failure: step 7: solver: residual is not finite");
  EXPECT_EQ(results[3].exitCode, 1);
  EXPECT_EQ(results[3].message, "internal: broken invariant");
  ASSERT_NE(firstFailure(results), nullptr);
  EXPECT_EQ(firstFailure(results), &results[1]);

  try {
    rethrowFailure(results[1]);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.path(), "cloths.0.mesh");
    EXPECT_EQ(e.reason(), "cannot read");
  }
  try {
    rethrowFailure(results[2]);
    ADD_FAILURE() << "no exception";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.step(), 7);
    EXPECT_EQ(e.module(), "solver");
    EXPECT_EQ(e.quantity(), "residual is not finite");
  }
  try {
    rethrowFailure(results[3]);
    ADD_FAILURE() << "no exception";
  } catch (const InputError&) {
    ADD_FAILURE() << "an internal error came back as bad input";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "broken invariant");
  }
  EXPECT_TRUE(failureIsShared());
}

TEST(SerialDistributor, RootFirstRunsTheStepOnce) {
  const auto workers = makeSerialDistributor();
  int runs = 0;
  workers->rootFirst([&] { ++runs; });
  EXPECT_EQ(runs, 1);
  EXPECT_THROW(workers->rootFirst([] { throw InputError("f", "p", "w"); }), InputError);
}

TEST(ProcessWorkers, WithoutALauncherIsThisProcessAlone) {
  // ctest starts this test without mpirun: no launcher variables, so no MPI either.
  EXPECT_EQ(launchRank(), 0);
  EXPECT_EQ(launchSize(), 1);
  EXPECT_EQ(processWorkers().size(), 1);
  EXPECT_EQ(processWorkers().description(), "serial");
}

}  // namespace
}  // namespace weft
