// An unattached cloth under gravity moves rigidly, and implicit Euler gives it exactly
// v_n = v_0 + n h g and x_n = x_0 + n h v_0 + g h^2 n (n + 1) / 2 (the cloth's internal forces
// vanish for a translation, so the PD solve is exact).

#include "PhysicsTestSupport.h"

#include <support/SceneBuilder.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

struct FreeFallCase {
  const char* name;
  Vec3 gravity;
  Vec3 initialVelocity;
  double dt;
  const char* method;        // "newton" or "pd"
  const char* acceleration;  // for "pd"
  double bend;
};

// Test names and failure messages show the case name, not the struct's bytes.
void PrintTo(const FreeFallCase& c, std::ostream* os) {
  *os << c.name;
}

class FreeFall : public ::testing::TestWithParam<FreeFallCase> {};

TEST_P(FreeFall, MatchesTheImplicitEulerClosedForm) {
  const FreeFallCase& p = GetParam();
  nlohmann::json doc = test::gridScene(0.6, 5, p.dt, 0, 800.0, p.bend);
  // A tilted, off-centre cloth, so no coordinate is trivially zero.
  doc["cloths"][0]["mesh"]["transform"] = {{"rotate_deg", {20, 35, -10}},
                                           {"translate", {0.3, 2.0, -0.4}}};
  doc["cloths"][0]["initial_velocity"] = {p.initialVelocity.x(), p.initialVelocity.y(),
                                          p.initialVelocity.z()};
  doc["gravity"] = {p.gravity.x(), p.gravity.y(), p.gravity.z()};
  doc["solver"]["method"] = p.method;
  doc["solver"]["acceleration"] = p.acceleration;
  const Scene scene = test::parse(doc);
  Simulator sim(scene);
  const NodeMatrix x0 = sim.positions();
  const double h = p.dt;
  for (int n = 1; n <= 25; ++n) {
    sim.step();
    const Eigen::RowVector3d shift =
        (n * h * p.initialVelocity + p.gravity * h * h * n * (n + 1) / 2.0).transpose();
    const Eigen::RowVector3d velocity = (p.initialVelocity + n * h * p.gravity).transpose();
    for (int i = 0; i < x0.rows(); ++i) {
      ASSERT_NEAR((sim.positions().row(i) - x0.row(i) - shift).norm(), 0.0, 1e-9)
          << "step " << n << ", vertex " << i;
      ASSERT_NEAR((sim.velocities().row(i) - velocity).norm(), 0.0, 1e-9)
          << "step " << n << ", vertex " << i;
    }
  }
  EXPECT_NEAR(sim.time(), 25 * h, 1e-12);
  EXPECT_EQ(sim.stepIndex(), 25);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FreeFall,
    ::testing::Values(FreeFallCase{"EarthGravityFromRest", Vec3(0, -9.8, 0), Vec3::Zero(), 0.01,
                                   "newton", "anderson", 0.0},
                      FreeFallCase{"EarthGravityFromRestPd", Vec3(0, -9.8, 0), Vec3::Zero(), 0.01,
                                   "pd", "anderson", 0.0},
                      FreeFallCase{"WithBendingPlainPd", Vec3(0, -9.8, 0), Vec3::Zero(), 0.01, "pd",
                                   "none", 0.002},
                      FreeFallCase{"SkewGravityLargeStep", Vec3(1.5, -9.8, 0.7), Vec3::Zero(),
                                   1.0 / 30.0, "newton", "anderson", 0.002},
                      FreeFallCase{"SkewGravityLargeStepPd", Vec3(1.5, -9.8, 0.7), Vec3::Zero(),
                                   1.0 / 30.0, "pd", "anderson", 0.002},
                      FreeFallCase{"ThrownUpwards", Vec3(0, -9.8, 0), Vec3(0.5, 3.0, -1.0), 0.005,
                                   "newton", "anderson", 0.001},
                      FreeFallCase{"ThrownUpwardsPd", Vec3(0, -9.8, 0), Vec3(0.5, 3.0, -1.0), 0.005,
                                   "pd", "anderson", 0.001}),
    [](const ::testing::TestParamInfo<FreeFallCase>& info) {
      return std::string(info.param.name);
    });

TEST(FreeFallTrajectory, RecordsEveryStateFromTheInitialOne) {
  nlohmann::json doc = test::gridScene(0.5, 3, 0.01, 0);
  doc["gravity"] = {0, -9.8, 0};
  const Scene scene = test::parse(doc);
  Simulator sim(scene);
  Trajectory trajectory;
  int calls = 0;
  sim.run(6, trajectory, [&](const StepStats& s) { EXPECT_EQ(s.step, ++calls); });
  EXPECT_EQ(calls, 6);
  ASSERT_EQ(trajectory.positions.size(), 7u);
  ASSERT_EQ(trajectory.velocities.size(), 7u);
  ASSERT_EQ(trajectory.stepCount(), 6);
  EXPECT_EQ(trajectory.nodeCount(), 16);
  EXPECT_EQ(trajectory.positions[0], scene.cloths[0].mesh.vertices);
  for (int n = 0; n <= 6; ++n)
    EXPECT_NEAR((trajectory.positions[n] - trajectory.positions[0]).col(1).maxCoeff(),
                -9.8 * 1e-4 * n * (n + 1) / 2, 1e-12);
  for (int n = 1; n <= 6; ++n) {
    EXPECT_EQ(trajectory.steps[n - 1].step, n);
    EXPECT_NEAR(trajectory.steps[n - 1].time, 0.01 * n, 1e-14);
    EXPECT_TRUE(trajectory.steps[n - 1].converged);
  }
  // positions.npy layout: [state][node][xyz], C order.
  const std::vector<double> flat = trajectory.flattenedPositions();
  ASSERT_EQ(flat.size(), 7u * 16u * 3u);
  EXPECT_EQ(flat[(5 * 16 + 9) * 3 + 2], trajectory.positions[5](9, 2));
}

TEST(FreeFallTrajectory, NoForcesMeansNoMotion) {
  const Scene scene = test::parse(test::gridScene(0.5, 3, 0.01, 0, 500.0, 0.01));
  Simulator sim(scene);
  for (int n = 0; n < 10; ++n) sim.step();
  // At rest every projection equals A x up to round-off, so the state moves by round-off only.
  EXPECT_LT((sim.positions() - scene.cloths[0].mesh.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(test::maxSpeed(sim.velocities()), 1e-10);
}

}  // namespace
}  // namespace weft
