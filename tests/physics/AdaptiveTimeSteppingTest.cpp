// Adaptive time stepping (SolverSettings::maxHalvings, Simulator::step): a step that does not
// converge is solved again as two halves, recursively, and the trajectory still records states
// at the scene's dt, with each split step's pieces kept for the backward pass.

#include <support/SceneBuilder.h>
#include <weft/physics/Model.h>
#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace weft {
namespace {

// A small cloth sliding over a sphere, solved with the Newton contact solve to 1e-9 m/s^2 with
// a budget of 12 linear solves per step: too few for the scene's 10 ms steps (they need 17-29),
// enough for their quarters.
nlohmann::json tightBudgetScene(int maxHalvings) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "sphere", "time": {"dt": 0.01, "steps": 15}, "gravity": [0.5, -9.8, 0],
    "solver": {"method": "newton", "contact": "newton", "pd_iterations": 12, "pd_tolerance": 1e-9},
    "cloths": [{"mesh": {"grid": {"size": [0.06, 0.06], "resolution": [3, 3]},
                         "transform": {"translate": [0, 0.3005, 0]}},
                "material": {"density": 1.0, "stretch": 20.0, "bend": 0.0005},
                "initial_velocity": [0.3, 0, 0.1]}],
    "obstacles": [{"sphere": {"center": [0, 0, 0], "radius": 0.3}, "friction": 0.1}]})");
  doc["solver"]["max_halvings"] = maxHalvings;
  return doc;
}

TEST(AdaptiveTimeStepping, WithoutHalvingsTheTightBudgetLeavesStepsUnconverged) {
  // The scene is hard enough to need the fallback: whole steps stop at the budget.
  Simulator sim(test::parse(tightBudgetScene(0)));
  Trajectory t;
  sim.run(15, t);
  int converged = 0;
  for (const StepStats& s : t.steps) {
    converged += s.converged;
    EXPECT_EQ(s.substeps, 1);
  }
  EXPECT_LT(converged, 3);
  for (const auto& pieces : t.substeps) EXPECT_TRUE(pieces.empty());
}

TEST(AdaptiveTimeStepping, UnconvergedStepsAreSplitUntilEveryPieceConverges) {
  const Scene scene = test::parse(tightBudgetScene(4));
  Simulator sim(scene);
  Trajectory t;
  sim.run(15, t);
  ASSERT_EQ(t.stepCount(), 15);
  ASSERT_EQ(t.substeps.size(), 15u);
  const double dt = scene.time.dt;
  for (int n = 0; n < 15; ++n) {
    SCOPED_TRACE(n);
    const StepStats& s = t.steps[n];
    const auto& pieces = t.substeps[n];
    EXPECT_TRUE(s.converged);
    EXPECT_LT(s.residual, 1e-9);
    EXPECT_NEAR(s.time, (n + 1) * dt, 1e-12);  // states stay on the scene's time grid
    ASSERT_GE(pieces.size(), 2u);
    EXPECT_EQ(s.substeps, static_cast<int>(pieces.size()));
    // The pieces tile the step: each starts where the previous one ended, their dts add up to
    // the scene's, and the step's state is the last one's end.
    double covered = 0.0;
    int deepest = 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const Substep& p = pieces[k];
      const double h = dt / std::ldexp(1.0, p.halvings);
      EXPECT_DOUBLE_EQ(p.model->dt(), h);
      covered += h;
      deepest = std::max(deepest, p.halvings);
      EXPECT_NEAR(p.time, n * dt + covered, 1e-12);
      const NodeMatrix& before = k == 0 ? t.positions[n] : pieces[k - 1].x1;
      EXPECT_EQ((p.x0 - before).norm(), 0.0);
      if (k > 0) {  // v0: the previous piece's (x1 - x0) / h
        const double hPrevious = dt / std::ldexp(1.0, pieces[k - 1].halvings);
        EXPECT_LT((p.v0 - (p.x0 - pieces[k - 1].x0) / hPrevious).norm(), 1e-9);
      }
    }
    EXPECT_NEAR(covered, dt, 1e-15);
    EXPECT_EQ(s.halvings, deepest);
    EXPECT_EQ((pieces.back().x1 - t.positions[n + 1]).norm(), 0.0);
    // The recorded velocity is the last piece's (x1 - x0) / h.
    const double hLast = dt / std::ldexp(1.0, pieces.back().halvings);
    EXPECT_LT((t.velocities[n + 1] - (pieces.back().x1 - pieces.back().x0) / hLast).norm(), 1e-9);
  }
}

TEST(AdaptiveTimeStepping, SplitStepsAgreeWithTheSameSceneRunAtTheFinerStep) {
  // Physics, not bookkeeping: where every step is split into quarters, the states are those of
  // the scene simulated at dt / 4 throughout (each converged to 1e-9 m/s^2).
  nlohmann::json doc = tightBudgetScene(2);
  doc["solver"]["pd_iterations"] = 200;  // (no budget pressure: compared at dt / 4 directly)
  nlohmann::json fine = doc;
  fine["time"]["dt"] = 0.0025;
  fine["time"]["steps"] = 60;
  Simulator fineSim(test::parse(fine));
  Trajectory reference;
  fineSim.run(60, reference);

  // The split run: a budget (14 solves) that fails the first steps whole and halved and passes
  // them in quarters. Steps whose pieces are all quarters are compared, up to the first that
  // is not.
  doc["solver"]["pd_iterations"] = 14;
  Simulator sim(test::parse(doc));
  Trajectory t;
  sim.run(15, t);
  int compared = 0;
  bool allQuartersSoFar = true;
  for (int n = 0; n < 15; ++n) {
    bool quarters = t.substeps[n].size() == 4;
    for (const Substep& p : t.substeps[n]) quarters = quarters && p.halvings == 2;
    allQuartersSoFar = allQuartersSoFar && quarters;
    if (!allQuartersSoFar) break;
    EXPECT_LT((t.positions[n + 1] - reference.positions[4 * (n + 1)]).cwiseAbs().maxCoeff(), 1e-9);
    ++compared;
  }
  EXPECT_GE(compared, 4);
}

TEST(AdaptiveTimeStepping, RememberedHalvingsStartWhereTheLastStepNeeded) {
  // solver.remember_halvings: where every whole step fails (the tight budget), the first step
  // fails whole and the next ones start split, so the whole-step attempts the plain run makes
  // on every step (and pays a budget for) are skipped, and every step still converges.
  nlohmann::json doc = tightBudgetScene(4);
  Simulator plain(test::parse(doc));
  Trajectory a;
  plain.run(15, a);
  doc["solver"]["remember_halvings"] = true;
  Simulator remembering(test::parse(doc));
  Trajectory b;
  remembering.run(15, b);
  long long plainSolves = 0, rememberingSolves = 0;
  for (int n = 0; n < 15; ++n) {
    SCOPED_TRACE(n);
    EXPECT_TRUE(a.steps[n].converged);
    EXPECT_TRUE(b.steps[n].converged);
    plainSolves += a.steps[n].pdIterations;
    rememberingSolves += b.steps[n].pdIterations;
    // From step 2 on, a step costs at least the failed whole attempt's budget (12 solves) less
    // with the memory (StepStats::pdIterations counts every attempt's solves).
    if (n >= 1) {
      EXPECT_LE(b.steps[n].pdIterations + 12, a.steps[n].pdIterations);
    }
  }
  std::printf("tight budget, 15 steps: %lld solves plain, %lld remembering the halvings\n",
              plainSolves, rememberingSolves);
  // Both converged runs are the same motion up to the split pattern's O(h) difference.
  EXPECT_LT((a.positions.back() - b.positions.back()).cwiseAbs().maxCoeff(), 1e-3);
}

}  // namespace
}  // namespace weft
