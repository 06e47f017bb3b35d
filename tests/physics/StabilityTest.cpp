// Hard cases stay numerically stable: very stiff cloth at a large time step, very soft cloth,
// a huge time step and a long run. Every state must be finite, with bounded speeds and sane
// edge lengths. And when each step is solved to convergence, implicit Euler only dissipates:
// without energy input the total energy never rises.

#include "PhysicsTestSupport.h"

#include <support/SceneBuilder.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

namespace weft {
namespace {

constexpr double kMaxSpeed = 100.0;  // m/s: nothing in these scenes comes near it
constexpr double kMinEdgeRatio = 0.1, kMaxEdgeRatio = 10.0;

struct StabilityCase {
  const char* name;
  double stretch;  // N/m
  double bend;     // N m
  double dt;       // s
  int steps;
  int quads;
  bool wind;         // sinusoidal wind (energy input)
  int pdIterations;  // cap per step
  double tolerance;  // PD tolerance, m/s^2
};

void PrintTo(const StabilityCase& c, std::ostream* os) {
  *os << c.name;
}

// Starts horizontal, pinned at the two corners of one edge: it swings down and whips.
nlohmann::json sceneFor(const StabilityCase& p, const std::string& method) {
  nlohmann::json doc = test::gridScene(0.5, p.quads, p.dt, 0, p.stretch, p.bend, 0.1);
  doc["gravity"] = {0, -9.8, 0};
  doc["cloths"][0]["attachments"] = {{{"vertices", {0, p.quads}}, {"kind", "fixed"}}};
  // Whole steps: these cases are about how each solver survives steps it cannot converge (the
  // very stiff cloth at 1/30 s converges none of its 150 steps, whole or split down to dt / 16,
  // where the split pieces reached 100.7 m/s against the bound's 100; issue 36's note).
  doc["solver"] = {{"method", method},
                   {"pd_iterations", p.pdIterations},
                   {"pd_tolerance", p.tolerance},
                   {"max_halvings", 0}};
  if (p.wind) doc["wind"] = {{"direction", {0.3, 0.0, 1.0}}, {"strength", 2.0}, {"frequency", 1.5}};
  return doc;
}

// Kinetic + gravitational + elastic (constraints, including the pins' springs) energy.
double totalEnergy(const Simulator& sim) {
  const Eigen::VectorXd& m = sim.cloth().mass;
  const double kinetic = 0.5 * (m.array() * sim.velocities().rowwise().squaredNorm().array()).sum();
  const double gravitational =
      -(m.array() * (sim.positions() * *sim.scene().gravity).array()).sum();
  return kinetic + gravitational + test::constraintEnergy(sim, sim.positions());
}

// Every case with both forward solvers.
using CaseAndSolver = std::tuple<StabilityCase, std::string>;

std::string caseName(const ::testing::TestParamInfo<CaseAndSolver>& info) {
  return std::string(std::get<0>(info.param).name) + "_" + std::get<1>(info.param);
}

class Stability : public ::testing::TestWithParam<CaseAndSolver> {};

TEST_P(Stability, StaysFiniteBoundedAndSane) {
  const StabilityCase& p = std::get<0>(GetParam());
  const Scene scene = test::parse(sceneFor(p, std::get<1>(GetParam())));
  Simulator sim(scene);
  double worstSpeed = 0, lowest = 1, highest = 1;
  for (int n = 1; n <= p.steps; ++n) {
    ASSERT_NO_THROW(sim.step()) << "step " << n;
    ASSERT_TRUE(sim.positions().allFinite()) << "step " << n;
    ASSERT_TRUE(sim.velocities().allFinite()) << "step " << n;
    const double speed = test::maxSpeed(sim.velocities());
    const auto [lo, hi] = test::edgeStretchRange(sim.cloth().rest, sim.positions());
    worstSpeed = std::max(worstSpeed, speed);
    lowest = std::min(lowest, lo);
    highest = std::max(highest, hi);
    ASSERT_LT(speed, kMaxSpeed) << "step " << n;
    ASSERT_GT(lo, kMinEdgeRatio) << "step " << n;
    ASSERT_LT(hi, kMaxEdgeRatio) << "step " << n;
  }
  RecordProperty("max_speed", std::to_string(worstSpeed));
  RecordProperty("edge_ratio_range", std::to_string(lowest) + " " + std::to_string(highest));
  // The cloth really moved (a frozen simulation would pass the bounds trivially).
  EXPECT_GT((sim.positions() - sim.cloth().rest.vertices).cwiseAbs().maxCoeff(), 0.1);
}

INSTANTIATE_TEST_SUITE_P(
    HardCases, Stability,
    ::testing::Combine(
        ::testing::Values(
            StabilityCase{"VeryStiffAtLargeStep", 1e6, 1e-3, 1.0 / 30.0, 150, 8, false, 200, 1e-6},
            StabilityCase{"VerySoft", 1.0, 1e-5, 0.01, 300, 8, false, 200, 1e-6},
            StabilityCase{"HugeTimeStep", 1000.0, 1e-3, 0.1, 100, 8, false, 200, 1e-6},
            StabilityCase{"LongRunInWind", 500.0, 1e-4, 0.01, 2000, 4, true, 200, 1e-6}),
        ::testing::Values("newton", "pd")),
    caseName);

class ConvergedStability : public ::testing::TestWithParam<CaseAndSolver> {};

TEST_P(ConvergedStability, NeverCreatesEnergy) {
  const StabilityCase& p = std::get<0>(GetParam());
  const Scene scene = test::parse(sceneFor(p, std::get<1>(GetParam())));
  Simulator sim(scene);
  // Energy scale: the work gravity can do over the cloth's size.
  const double scale = sim.cloth().mass.sum() * 9.8 * 0.5;
  double previous = totalEnergy(sim);
  int unconverged = 0;
  for (int n = 1; n <= p.steps; ++n) {
    const StepStats& stats = sim.step();
    unconverged += stats.converged ? 0 : 1;
    const double energy = totalEnergy(sim);
    ASSERT_LE(energy, previous + 1e-6 * scale)
        << "step " << n << ": energy rose by " << energy - previous << " J (" << stats.pdIterations
        << " iterations, residual " << stats.residual << " m/s^2)";
    previous = energy;
  }
  EXPECT_EQ(unconverged, 0) << "the premise: every step solved to tolerance";
}

INSTANTIATE_TEST_SUITE_P(
    HardCases, ConvergedStability,
    ::testing::Combine(::testing::Values(StabilityCase{"VerySoft", 1.0, 1e-5, 0.01, 300, 8, false,
                                                       20000, 1e-7},
                                         StabilityCase{"HugeTimeStep", 1000.0, 1e-3, 0.1, 100, 8,
                                                       false, 20000, 1e-7}),
                       ::testing::Values("newton", "pd")),
    caseName);

// At 1e6 N/m round-off alone leaves residuals near 1e-7 m/s^2, so converge to 1e-4. Only Newton:
// PD (with or without Anderson) stays above 1e-4 m/s^2 even after 20000 iterations per step
// here, so the premise of the test cannot be met with it.
INSTANTIATE_TEST_SUITE_P(StiffNewton, ConvergedStability,
                         ::testing::Combine(::testing::Values(StabilityCase{
                                                "VeryStiffAtLargeStep", 1e6, 1e-3, 1.0 / 30.0, 60,
                                                6, false, 20000, 1e-4}),
                                            ::testing::Values("newton")),
                         caseName);

}  // namespace
}  // namespace weft
