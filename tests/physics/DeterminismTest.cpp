// The same scene simulated twice gives bit-identical positions, also with several threads
// (reproducible runs are part of the contract for batch use and for the backward pass).

#include <support/SceneBuilder.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <string>

namespace weft {
namespace {

std::vector<double> simulate(const Scene& scene, int steps) {
  Simulator sim(scene);
  Trajectory trajectory;
  sim.run(steps, trajectory);
  return trajectory.flattenedPositions();
}

class Determinism : public ::testing::TestWithParam<std::string> {};

TEST_P(Determinism, SameSceneTwiceIsBitIdentical) {
  nlohmann::json doc = test::hangingClothScene(0.5, 6, 0.01, 0, 800.0, 1e-3);
  doc["wind"] = {{"direction", {0.2, 0.0, 1.0}}, {"strength", 1.5}, {"frequency", 2.0}};
  // A loose tolerance: iterations stop mid-convergence, where any difference would show.
  doc["solver"] = {{"method", GetParam()}, {"pd_iterations", 100}, {"pd_tolerance", 1e-3}};
  const Scene scene = test::parse(doc);
  const int threadsBefore = omp_get_max_threads();
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    const std::vector<double> a = simulate(scene, 30);
    const std::vector<double> b = simulate(scene, 30);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0)
        << threads << " threads";
    // Not a trivially static scene.
    EXPECT_GT(std::abs(a.back() - a[a.size() - 1 - 3 * 49 * 30]), 1e-3);
  }
  omp_set_num_threads(threadsBefore);
}

INSTANTIATE_TEST_SUITE_P(Solvers, Determinism, ::testing::Values("newton", "pd"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace weft
