// The three adjoint linear solvers (fixed point, GMRES, direct LU) on the same steps: the same
// solution and the same gradient; the assembled K agrees with its matrix-free product; and a
// case built so that the fixed-point iteration diverges (stiff cloth under compression, where
// rho(P^{-1} Delta P) > 1) is detected and still yields the correct gradient.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/AdjointSolver.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ContactAdjoint.h>
#include <weft/diff/DirectLuSolver.h>
#include <weft/diff/FixedPointSolver.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GmresSolver.h>
#include <weft/diff/GradientCheck.h>
#include <weft/io/Npy.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace weft {
namespace {

using test::TempDir;

NodeMatrix randomBlock(int m, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  NodeMatrix b(m, 3);
  for (int i = 0; i < m; ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = n(gen);
  return b;
}

// The adjoint system at the last state of `document`'s forward run, converged to 1e-8.
std::unique_ptr<AdjointSystem> systemAtLastState(const nlohmann::json& document) {
  const Scene scene = withTightForwardSolver(test::parse(document), 1e-8);
  const ForwardPass pass = runForwardPass(scene);
  auto system = std::make_unique<AdjointSystem>(pass.trajectory.model);
  system->prepare(pass.trajectory.positions.back());
  return system;
}

TEST(AdjointSystem, AssembledMatrixMatchesTheProductAndIsSymmetric) {
  const std::unique_ptr<AdjointSystem> prepared = systemAtLastState(test::windClothScene(6, 15));
  AdjointSystem& system = *prepared;
  ASSERT_TRUE(system.hasDeltaP());
  const Eigen::SparseMatrix<double> k = system.assembleK();
  const int m = system.nodeCount();
  const NodeMatrix x = randomBlock(m, 1);
  NodeMatrix kx(m, 3);
  system.multiplyK(x, kx);
  const Eigen::Map<const Eigen::VectorXd> flat(x.data(), 3 * m);
  const Eigen::VectorXd assembled = k * flat;
  const Eigen::Map<const Eigen::VectorXd> product(kx.data(), 3 * m);
  EXPECT_LT((assembled - product).norm(), 1e-12 * product.norm());
  const Eigen::SparseMatrix<double> kt = k.transpose();
  EXPECT_LT((k - kt).norm(), 1e-10 * k.norm());
}

// One recorded contact step of a forward run converged to 1e-8, prepared as Backpropagation
// prepares it (the trajectory's model outlives the system and the contact part, which refer to
// it).
struct ContactStep {
  Scene scene;
  Trajectory trajectory;
  std::unique_ptr<AdjointSystem> system;
  std::unique_ptr<ContactAdjoint> contact;
};

std::unique_ptr<ContactStep> lastContactStep(const nlohmann::json& document) {
  auto s = std::make_unique<ContactStep>();
  s->scene = withTightForwardSolver(test::parse(document), 1e-8);
  s->trajectory = runForwardPass(s->scene).trajectory;
  const int n = s->trajectory.stepCount() - 1;
  const double h = s->scene.time.dt, t1 = h * (n + 1);
  s->system = std::make_unique<AdjointSystem>(s->trajectory.model);
  s->contact = std::make_unique<ContactAdjoint>(*s->trajectory.model);
  s->contact->prepare(s->trajectory.contacts[n], s->trajectory.positions[n], t1 - h, t1, n + 1);
  s->system->prepare(s->trajectory.positions[n + 1], s->contact.get());
  return s;
}

// A cloth resting on a sphere (friction 0.9: its contacts stick) and a ribbon sliding down an
// incline (they slip), 8 x 8 and 12 x 4 quads.
nlohmann::json restingOnASphere() {
  return nlohmann::json::parse(R"({
    "name": "resting", "time": {"dt": 0.01, "steps": 10}, "gravity": [0, -9.8, 0],
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4},
    "cloths": [{"mesh": {"grid": {"size": [0.1, 0.1], "resolution": [8, 8]},
                         "transform": {"translate": [0, 0.3005, 0]}},
                "material": {"density": 1.0, "stretch": 20.0, "bend": 0.0005}}],
    "obstacles": [{"sphere": {"center": [0, 0, 0], "radius": 0.3}, "friction": 0.9}]})");
}

nlohmann::json slidingRibbon() {
  nlohmann::json doc = test::inclineScene();
  doc["cloths"][0]["mesh"]["grid"]["resolution"] = {12, 4};
  return doc;
}

// The ribbon released at rest with friction 0.36, just below tan 20 deg = 0.364: it creeps, and
// friction takes 72 % of each node's tangential trial velocity (S's tangent block has the
// eigenvalue 1 - g = 0.28 across the slip).
nlohmann::json creepingRibbon() {
  nlohmann::json doc = slidingRibbon();
  doc["obstacles"][0]["friction"] = 0.36;
  doc["cloths"][0]["initial_velocity"] = {0.0, 0.0, 0.0};
  return doc;
}

// A 4 x 4-quad cloth resting on another held fixed at every node, 20 mm (the collision
// distance) above it, node over node 40 mm apart: every upper node has one self-collision pair
// and no other contact. Gravity is tilted by `tilt` (its tangential part over its normal part);
// with a pair friction above it the pairs stick, below it they slip.
nlohmann::json restingOnAFixedCloth(double friction, double tilt) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "stacked", "time": {"dt": 0.01, "steps": 8},
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4}})");
  doc["gravity"] = {9.8 * tilt, -9.8, 0.0};
  for (int k = 0; k < 2; ++k) {
    nlohmann::json cloth = {{"mesh",
                             {{"grid", {{"size", {0.16, 0.16}}, {"resolution", {4, 4}}}},
                              {"transform", {{"translate", {0.0, 0.02 * k, 0.0}}}}}},
                            {"material", {{"density", 1.0}, {"stretch", 20.0}, {"bend", 0.0005}}},
                            {"self_collision", {{"radius", 0.02}, {"friction", friction}}}};
    if (k == 0) {
      std::vector<int> all(25);
      for (int i = 0; i < 25; ++i) all[i] = i;
      cloth["attachments"] = {{{"vertices", all}, {"kind", "fixed"}}};
    }
    doc["cloths"].push_back(cloth);
  }
  return doc;
}

// The pairs of a step by branch: (node, partner) of each.
std::vector<std::pair<int, int>> pairsOn(const StepContacts& contacts, ContactBranch branch) {
  std::vector<std::pair<int, int>> pairs;
  for (const ContactPoint& p : contacts.points)
    if (p.partner >= 0 && p.branch == branch) pairs.emplace_back(p.node, p.partner);
  return pairs;
}

// For a g on prescribed velocities only, the contact preconditioner gives M^-1 g, and K of it is g
// to round-off; without its contact part, the factor's solve of the same g is far from K's
// inverse.
void expectInvertedExactly(AdjointSystem& system, const NodeMatrix& g) {
  ASSERT_TRUE(system.hasContact());
  NodeMatrix z = g, kz;
  system.precondition(z, false);
  EXPECT_LT((z - system.cloth().mass.cwiseInverse().asDiagonal() * g).norm(), 1e-12 * z.norm());
  system.multiplyK(z, kz);
  EXPECT_LT((kz - g).norm(), 1e-12 * g.norm());
  system.setContactPreconditioning(false);
  system.precondition(z = g, false);
  system.multiplyK(z, kz);
  EXPECT_GT((kz - g).norm(), 0.1 * g.norm());
  system.setContactPreconditioning(true);
}

// GMRES to 1e-10 with and without the contact part of the preconditioner: both reach the direct
// solve's solution, the contact part in fewer iterations.
void expectFewerIterationsAndTheSameSolution(AdjointSystem& system, unsigned seed,
                                             const std::string& label) {
  ASSERT_TRUE(system.hasContact());
  const NodeMatrix g = randomBlock(system.nodeCount(), seed);
  NodeMatrix exact, a, b;
  ASSERT_TRUE(DirectLuSolver().solve(system, g, exact).converged);
  GmresSolver withContact(1e-10, 1000, 1000), factorOnly(1e-10, 1000, 1000);
  const LinearSolveResult ra = withContact.solve(system, g, a);
  system.setContactPreconditioning(false);
  const LinearSolveResult rb = factorOnly.solve(system, g, b);
  system.setContactPreconditioning(true);
  ASSERT_TRUE(ra.converged);
  ASSERT_TRUE(rb.converged);
  EXPECT_LT((a - exact).norm(), 1e-8 * exact.norm());
  EXPECT_LT((b - exact).norm(), 1e-8 * exact.norm());
  std::printf(
      "%s: iterations to 1e-10 preconditioned by P with the contact part %d, by P alone %d\n",
      label.c_str(), ra.iterations, rb.iterations);
  EXPECT_LT(ra.iterations, rb.iterations);
}

// With contact, GMRES's preconditioner inverts the columns of K that belong to the velocities
// the contacts prescribe (AdjointSystem::precondition): where a node sticks, S = 0 and K's
// column block there is M alone, so for a right-hand side on stuck nodes only the preconditioned
// vector is M^-1 g and K of it is g, to round-off.
TEST(AdjointSolvers, ContactPreconditionerInvertsStuckNodesExactly) {
  const std::unique_ptr<ContactStep> step = lastContactStep(restingOnASphere());
  AdjointSystem& system = *step->system;
  ASSERT_TRUE(system.hasContact());
  const int m = system.nodeCount();
  NodeMatrix g = NodeMatrix::Zero(m, 3);
  const NodeMatrix noise = randomBlock(m, 11);
  int stuck = 0;
  for (const ContactPoint& p : step->trajectory.contacts.back().points)
    if (p.branch == ContactBranch::Stick && p.partner < 0)
      g.row(p.node) = noise.row(p.node), ++stuck;
  ASSERT_GE(stuck, 10);
  expectInvertedExactly(system, g);
}

// On whole steps, sticking and slipping, the contact preconditioner reaches the direct solve's
// solution in fewer GMRES iterations than the factor alone.
TEST(AdjointSolvers, ContactPreconditionerCutsIterationsAndKeepsTheSolution) {
  for (const nlohmann::json& doc : {restingOnASphere(), slidingRibbon()}) {
    const std::unique_ptr<ContactStep> step = lastContactStep(doc);
    expectFewerIterationsAndTheSameSolution(*step->system, 12, step->scene.name);
  }
}

// Where friction takes most of a slipping node's tangential velocity, z's tangent part is the
// factor's solution mapped through S's inverse there (AdjointSystem::precondition): 24
// iterations to 1e-10 on the creeping ribbon; a build with the map replaced by the tangent
// projector took 36 there, which this bound catches (P alone: 148).
TEST(AdjointSolvers, ContactPreconditionerMapsSlipsThroughFriction) {
  const std::unique_ptr<ContactStep> step = lastContactStep(creepingRibbon());
  AdjointSystem& system = *step->system;
  ASSERT_TRUE(system.hasContact());
  int slipping = 0;
  for (const ContactPoint& p : step->trajectory.contacts.back().points)
    slipping += p.branch == ContactBranch::Slip;
  ASSERT_GE(slipping, 40);
  const NodeMatrix g = randomBlock(system.nodeCount(), 13);
  NodeMatrix exact, z;
  ASSERT_TRUE(DirectLuSolver().solve(system, g, exact).converged);
  const LinearSolveResult r = GmresSolver(1e-10, 1000, 1000).solve(system, g, z);
  ASSERT_TRUE(r.converged);
  EXPECT_LT((z - exact).norm(), 1e-8 * exact.norm());
  EXPECT_LE(r.iterations, 30);
}

// A self-collision pair prescribes its nodes' relative velocity: where it sticks, z = (e / m_a,
// -e / m_b) has S z = 0 and K z = (e, -e), so for a right-hand side that pulls a stuck pair's
// nodes apart (g_b = -g_a) the preconditioned vector is M^-1 g and K of it is g, to round-off.
TEST(AdjointSolvers, ContactPreconditionerInvertsStuckPairsExactly) {
  const std::unique_ptr<ContactStep> step = lastContactStep(restingOnAFixedCloth(0.9, 0.2));
  AdjointSystem& system = *step->system;
  ASSERT_TRUE(system.hasContact());
  const auto stuck = pairsOn(step->trajectory.contacts.back(), ContactBranch::Stick);
  ASSERT_EQ(stuck.size(), 25u);
  const int m = system.nodeCount();
  NodeMatrix g = NodeMatrix::Zero(m, 3);
  const NodeMatrix noise = randomBlock(m, 14);
  for (const auto& [a, b] : stuck) g.row(a) = noise.row(a), g.row(b) = -noise.row(a);
  expectInvertedExactly(system, g);
}

// Whole steps with pairs, stuck and slipping: fewer GMRES iterations than the factor alone, and
// the direct solve's solution.
TEST(AdjointSolvers, ContactPreconditionerCutsIterationsOnPairs) {
  for (const double friction : {0.9, 0.1}) {
    const std::unique_ptr<ContactStep> step = lastContactStep(restingOnAFixedCloth(friction, 0.2));
    const ContactBranch branch = friction > 0.2 ? ContactBranch::Stick : ContactBranch::Slip;
    ASSERT_EQ(pairsOn(step->trajectory.contacts.back(), branch).size(), 25u);
    expectFewerIterationsAndTheSameSolution(*step->system, 15,
                                            "pairs, friction " + std::to_string(friction));
  }
}

// The spectral radius of P^{-1} Delta P at the system's prepared state (power iteration; the
// matrix is similar to the symmetric P^{-1/2} Delta P P^{-1/2}, so this converges to |lambda|max).
double fixedPointSpectralRadius(AdjointSystem& system) {
  NodeMatrix u = randomBlock(system.nodeCount(), 3), w;
  double rho = 0.0;
  for (int k = 0; k < 200; ++k) {
    u /= u.norm();
    system.multiplyDeltaP(u, w);
    system.solveP(w);
    rho = w.norm();
    u.swap(w);
  }
  return rho;
}

TEST(AdjointSolvers, AllThreeGiveTheSameSolution) {
  const std::unique_ptr<AdjointSystem> prepared =
      systemAtLastState(test::softWindClothScene(6, 15));
  AdjointSystem& system = *prepared;
  EXPECT_LT(fixedPointSpectralRadius(system), 1.0);
  const NodeMatrix g = randomBlock(system.nodeCount(), 2);
  FixedPointSolver fixedPoint(1e-12, 500);
  GmresSolver gmres(1e-12, 500);
  DirectLuSolver direct;
  NodeMatrix a, b, c;
  const LinearSolveResult ra = fixedPoint.solve(system, g, a);
  const LinearSolveResult rb = gmres.solve(system, g, b);
  const LinearSolveResult rc = direct.solve(system, g, c);
  ASSERT_TRUE(ra.converged);
  ASSERT_TRUE(rb.converged);
  ASSERT_TRUE(rc.converged);
  EXPECT_LT(ra.residual, 1e-12);
  EXPECT_LT(rb.residual, 1e-12);
  EXPECT_LT(rc.residual, 1e-12);
  EXPECT_LT((a - c).norm(), 1e-9 * c.norm());
  EXPECT_LT((b - c).norm(), 1e-9 * c.norm());
  EXPECT_LT(rb.iterations, ra.iterations + 1);
}

// Backpropagation hands each step's GMRES the previous step's z as its starting point. From the
// exact solution it must stop at once; from a perturbed one it must reach the same solution as
// from zero, with fewer iterations when the guess is close.
TEST(AdjointSolvers, GmresWarmStartReachesTheSameSolution) {
  const std::unique_ptr<AdjointSystem> prepared = systemAtLastState(test::windClothScene(6, 15));
  AdjointSystem& system = *prepared;
  const NodeMatrix g = randomBlock(system.nodeCount(), 4);
  GmresSolver cold(1e-10, 500, 500), warm(1e-10, 500, 500, /*warmStart=*/true);
  NodeMatrix fromZero = NodeMatrix::Constant(system.nodeCount(), 3, 7.0);  // ignored: cold start
  const LinearSolveResult r0 = cold.solve(system, g, fromZero);
  ASSERT_TRUE(r0.converged);
  NodeMatrix exact = fromZero;
  const LinearSolveResult r1 = warm.solve(system, g, exact);
  EXPECT_TRUE(r1.converged);
  EXPECT_EQ(r1.iterations, 0);
  NodeMatrix near =
      fromZero + 1e-3 * randomBlock(system.nodeCount(), 5) * (fromZero.norm() / fromZero.size());
  const LinearSolveResult r2 = warm.solve(system, g, near);
  ASSERT_TRUE(r2.converged);
  EXPECT_LT(r2.iterations, r0.iterations);
  EXPECT_LT((near - fromZero).norm(), 1e-8 * fromZero.norm());
}

// The clamped-Hessian preconditioner (solver.backward.preconditioner "hessian") solves the same
// system to the same solution as the direct LU, and on a hanging cloth in tension, where P is a
// poor model of K = P - Delta P, in a fraction of the iterations P needs.
TEST(AdjointSolvers, ClampedHessianPreconditionerNeedsFewIterations) {
  const std::unique_ptr<AdjointSystem> prepared = systemAtLastState(test::windClothScene(10, 20));
  AdjointSystem& system = *prepared;
  ASSERT_TRUE(system.hasDeltaP());
  const NodeMatrix g = randomBlock(system.nodeCount(), 6);
  GmresSolver byP(1e-10, 1000, 1000);
  GmresSolver byHessian(1e-10, 1000, 1000, false, GmresSolver::Preconditioner::ClampedHessian);
  DirectLuSolver direct;
  NodeMatrix a, b, c;
  const LinearSolveResult ra = byP.solve(system, g, a);
  const LinearSolveResult rb = byHessian.solve(system, g, b);
  ASSERT_TRUE(direct.solve(system, g, c).converged);
  ASSERT_TRUE(ra.converged);
  ASSERT_TRUE(rb.converged);
  EXPECT_LT((b - c).norm(), 1e-7 * c.norm());
  std::printf("iterations to 1e-10: preconditioned by P %d, by the clamped Hessian %d\n",
              ra.iterations, rb.iterations);
  EXPECT_LT(4 * rb.iterations, ra.iterations);
}

// The automatic preconditioner (solver.backward.preconditioner "auto", the default) starts with
// P and switches to the clamped Hessian once P needs more than kAutomaticPIterations iterations,
// keeping it for later solves; where P is a good model of K (soft cloth: Delta P small against
// the mass) it never factors the Hessian.
TEST(AdjointSolvers, AutomaticPreconditionerSwitchesToTheHessianOnlyWherePIsSlow) {
  {
    const std::unique_ptr<AdjointSystem> prepared = systemAtLastState(test::windClothScene(10, 20));
    AdjointSystem& system = *prepared;
    GmresSolver automatic(1e-10, 1000, 1000, false, GmresSolver::Preconditioner::Automatic);
    GmresSolver byHessian(1e-10, 1000, 1000, false, GmresSolver::Preconditioner::ClampedHessian);
    DirectLuSolver direct;
    EXPECT_STREQ(automatic.name(), "gmres (auto: p)");
    for (int seed : {6, 7}) {
      const NodeMatrix g = randomBlock(system.nodeCount(), seed);
      NodeMatrix a, b, c;
      const LinearSolveResult ra = automatic.solve(system, g, a);
      const LinearSolveResult rb = byHessian.solve(system, g, b);
      ASSERT_TRUE(direct.solve(system, g, c).converged);
      ASSERT_TRUE(ra.converged);
      EXPECT_LT((a - c).norm(), 1e-7 * c.norm());
      EXPECT_STREQ(automatic.name(), "gmres (auto: hessian)");
      std::printf("seed %d: automatic %d iterations, clamped Hessian %d\n", seed, ra.iterations,
                  rb.iterations);
      // First solve: P for as many iterations as a factorisation costs, shared by the steps a
      // factor is assumed to serve, then the Hessian from where P stopped; second: the Hessian
      // at once.
      const int budget = std::max(GmresSolver::kAutomaticPIterations,
                                  static_cast<int>(std::lround(system.hessianFactorCost() /
                                                               GmresSolver::kAutomaticPriorReuse)));
      if (seed == 6) {
        EXPECT_GT(ra.iterations, budget);
        EXPECT_LE(ra.iterations, budget + rb.iterations + 2);
      } else {
        EXPECT_EQ(ra.iterations, rb.iterations);
      }
    }
  }
  {
    const std::unique_ptr<AdjointSystem> prepared =
        systemAtLastState(test::softWindClothScene(6, 25));
    AdjointSystem& system = *prepared;
    ASSERT_TRUE(system.hasDeltaP());
    // At a backward pass's default tolerance, 1e-4, P needs under kAutomaticPIterations here.
    GmresSolver automatic(1e-4, 1000, 1000, false, GmresSolver::Preconditioner::Automatic);
    GmresSolver byP(1e-4, 1000, 1000);
    DirectLuSolver direct;
    const NodeMatrix g = randomBlock(system.nodeCount(), 8);
    NodeMatrix a, b, c;
    const LinearSolveResult ra = automatic.solve(system, g, a);
    const LinearSolveResult rb = byP.solve(system, g, b);
    ASSERT_TRUE(direct.solve(system, g, c).converged);
    ASSERT_TRUE(ra.converged);
    EXPECT_LT((a - c).norm(), 1e-3 * c.norm());
    std::printf("soft cloth: automatic %d iterations, P %d\n", ra.iterations, rb.iterations);
    EXPECT_EQ(ra.iterations, rb.iterations);
    EXPECT_LE(ra.iterations, GmresSolver::kAutomaticPIterations);
    EXPECT_STREQ(automatic.name(), "gmres (auto: p)");
  }
}

// The automatic choice depends on iteration and operation counts only, never on time: a
// repeated backward pass switches at the same steps and gives the same bits. (At a tolerance of
// 1e-10 P needs more iterations on this cloth in tension than a factorisation costs.)
TEST(AdjointSolvers, AutomaticPreconditionerRepeatsBitForBit) {
  TempDir dir;
  Scene scene = withTightForwardSolver(
      test::withTrajectoryTask(dir, test::windClothScene(10, 20),
                               {"cloths.0.material.stretch", "wind.strength"}),
      1e-8);
  ASSERT_EQ(scene.solver.backward.preconditioner, "auto");
  scene.solver.backward.tolerance = 1e-10;
  const ForwardPass pass = runForwardPass(scene);
  const TaskLoss loss(scene);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  const GradientResult a = backpropagate(pass.trajectory, loss, parameters, scene.solver.backward);
  const GradientResult b = backpropagate(pass.trajectory, loss, parameters, scene.solver.backward);
  EXPECT_EQ(a.solver.iterations, b.solver.iterations);
  for (int k = 0; k < parameters.size(); ++k)
    EXPECT_EQ(a.gradient[k], b.gradient[k]) << parameters[k].path;
  // It did switch: far fewer iterations than with P alone on this cloth in tension.
  BackwardSettings byP = scene.solver.backward;
  byP.preconditioner = "p";
  const GradientResult c = backpropagate(pass.trajectory, loss, parameters, byP);
  std::printf("iterations over %d steps: auto %lld, P %lld\n", a.solver.solves, a.solver.iterations,
              c.solver.iterations);
  EXPECT_LT(2 * a.solver.iterations, c.solver.iterations);
}

// Each step's GMRES starts from the best combination of the last solver.backward.history
// solutions (SolutionHistory): the same gradient as the direct solve, in fewer iterations than
// from the last step's solution alone.
TEST(AdjointSolvers, PreviousSolutionsCutIterationsAndKeepTheGradient) {
  TempDir dir;
  const Scene scene = withTightForwardSolver(
      test::withTrajectoryTask(dir, test::windClothScene(10, 40),
                               {"cloths.0.material.stretch", "wind.strength"}),
      1e-8);
  ASSERT_EQ(scene.solver.backward.history, 8);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  BackwardSettings settings = scene.solver.backward;
  settings.preconditioner = "p";
  settings.tolerance = 1e-8;
  settings.maxIterations = 1000;
  const test::HistoryGradients g = test::gradientsWithAndWithoutHistory(scene, settings);
  const GradientResult &direct = g.direct, &withHistory = g.combined, &lastOnly = g.lastOnly;
  std::printf("iterations over %d steps: last solution %lld, combination of the last 8 %lld\n",
              withHistory.solver.solves, lastOnly.solver.iterations, withHistory.solver.iterations);
  for (const GradientResult* r : {&withHistory, &lastOnly}) {
    EXPECT_EQ(r->solver.fallbacks, 0);
    for (int k = 0; k < parameters.size(); ++k)
      EXPECT_LT(relativeError(r->gradient[k], direct.gradient[k]), 1e-6) << parameters[k].path;
  }
  EXPECT_LT(withHistory.solver.iterations, 0.8 * lastOnly.solver.iterations);
}

// The automatic preconditioner weighs P against the clamped Hessian by operation counts: a
// factorisation costs hessianFactorCost() iterations with P, an iteration with H
// hessianIterationCost(). Over a backward pass its cost in those units stays close to the
// cheaper of P alone and the Hessian alone: on a stiff cloth in tension (P slow) and on a soft
// one (P fast), at a tight and a loose tolerance.
TEST(AdjointSolvers, AutomaticPreconditionerCostsAboutTheCheaperChoice) {
  struct Case {
    const char* name;
    nlohmann::json document;
    double tolerance;
  };
  const std::vector<Case> cases = {{"stiff, 1e-8", test::windClothScene(10, 40), 1e-8},
                                   {"stiff, 1e-4", test::windClothScene(10, 40), 1e-4},
                                   {"soft, 1e-8", test::softWindClothScene(10, 40), 1e-8},
                                   {"soft, 1e-4", test::softWindClothScene(10, 40), 1e-4}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    TempDir dir;
    const Scene scene = withTightForwardSolver(
        test::withTrajectoryTask(dir, c.document, {"cloths.0.material.stretch", "wind.strength"}),
        1e-8);
    const ForwardPass pass = runForwardPass(scene);
    const TaskLoss loss(scene);
    const ParameterSet parameters = ParameterSet::fromTask(scene);
    const AdjointSystem costs(pass.trajectory.model);
    BackwardSettings settings = scene.solver.backward;
    settings.tolerance = c.tolerance;
    settings.maxIterations = 1000;
    auto cost = [&](const char* preconditioner) {
      settings.preconditioner = preconditioner;
      const GradientResult r = backpropagate(pass.trajectory, loss, parameters, settings);
      EXPECT_EQ(r.solver.fallbacks, 0) << preconditioner;
      const AdjointSolverStats& s = r.solver;
      return double(s.iterations - s.hessianIterations) +
             costs.hessianIterationCost() * double(s.hessianIterations) +
             costs.hessianFactorCost() * s.hessianFactorizations;
    };
    const double automatic = cost("auto"), byP = cost("p"), byHessian = cost("hessian");
    std::printf("%s: cost in iterations with P: auto %.0f, P %.0f, Hessian %.0f\n", c.name,
                automatic, byP, byHessian);
    EXPECT_LT(automatic, 1.25 * std::min(byP, byHessian));
  }
}

TEST(AdjointSolvers, EveryMethodGivesTheSameGradient) {
  TempDir dir;
  const Scene scene = withTightForwardSolver(
      test::withTrajectoryTask(
          dir, test::softWindClothScene(6, 25),
          {"cloths.0.material.stretch", "wind.strength", "cloths.0.material.density"}),
      1e-8);
  const ForwardPass pass = runForwardPass(scene);
  const TaskLoss loss(scene);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  std::vector<Eigen::VectorXd> gradients;
  for (const char* method : {"direct", "fixed_point", "gmres"}) {
    BackwardSettings settings = scene.solver.backward;
    settings.method = method;
    settings.tolerance = 1e-9;
    settings.maxIterations = 1000;
    const GradientResult r = backpropagate(pass.trajectory, loss, parameters, settings);
    EXPECT_EQ(r.solver.fallbacks, 0) << method;
    EXPECT_EQ(r.solver.solves, scene.time.steps) << method;
    std::printf("%-11s %d steps, %lld iterations (max %d per step), %d fallbacks, %.4f s\n", method,
                r.solver.solves, r.solver.iterations, r.solver.maxIterations, r.solver.fallbacks,
                r.solver.seconds);
    gradients.push_back(r.gradient);
  }
  for (int k = 0; k < parameters.size(); ++k) {
    SCOPED_TRACE(parameters[k].path);
    EXPECT_LT(relativeError(gradients[1][k], gradients[0][k]), 1e-8);
    EXPECT_LT(relativeError(gradients[2][k], gradients[0][k]), 1e-8);
  }
}

// A flat cloth squeezed in its own plane (no gravity; left column fixed, right column a handle
// moving 0.1 m towards it in 0.1 s; wind along the squeeze): the triangles are compressed, so
// the out-of-plane derivative of the stretch projection, 1/sigma, exceeds 1 and rho(P^{-1}
// Delta P) grows to about 1.4 (measured): Eq. 20 diverges along the out-of-plane (buckling)
// modes. The forward stays exactly planar, hence smooth, and K stays non-singular (indefinite).
// The loss asks for an out-of-plane final shape, so that the adjoint right-hand side excites
// those modes.
nlohmann::json squeezedClothScene() {
  nlohmann::json doc = test::gridScene(0.3, 5, 0.01, 10, 1000.0, 0.0, 0.1);
  const nlohmann::json keyframes =
      nlohmann::json::array({{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}},
                             {{"time", 0.1}, {"offset", {-0.1, 0.0, 0.0}}}});
  nlohmann::json fixed = {{"vertices", {0, 6, 12, 18, 24, 30}}, {"kind", "fixed"}};
  nlohmann::json handle = {{"vertices", {5, 11, 17, 23, 29, 35}},
                           {"kind", "handle"},
                           {"trajectory", {{"keyframes", keyframes}}}};
  doc["cloths"][0]["attachments"] = nlohmann::json::array({fixed, handle});
  doc["wind"] = {
      {"direction", {1.0, 0.0, 0.0}}, {"strength", 0.5}, {"frequency", 1.0}, {"phase", 0.0}};
  return doc;
}

TEST(AdjointSolvers, DivergingFixedPointIsDetectedAndFallsBack) {
  TempDir dir;
  nlohmann::json doc = squeezedClothScene();
  {
    // Target: the final state of the run, lifted out of plane by 1 cm.
    const ForwardPass run = runForwardPass(withTightForwardSolver(test::parse(doc), 1e-8));
    NodeMatrix target = run.trajectory.positions.back();
    target.col(1).array() += 0.01;
    target.col(0).array() += 0.005;  // and shifted in plane, so that every parameter matters
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows = target;
    writeNpy(dir.file("lifted.npy"), {static_cast<std::size_t>(rows.rows()), 3}, rows.data());
  }
  test::addTask(doc, "final", dir.file("lifted.npy"),
                {"wind.strength", "wind.phase", "cloths.0.material.stretch"});
  const Scene scene = withTightForwardSolver(test::parse(doc), 1e-8);
  const ForwardPass pass = runForwardPass(scene);
  ASSERT_EQ(pass.unconvergedSteps, 0);

  // The spectral radius of P^{-1} Delta P at the last state exceeds 1.
  AdjointSystem system(pass.trajectory.model);
  system.prepare(pass.trajectory.positions.back());
  const double rho = fixedPointSpectralRadius(system);
  EXPECT_GT(rho, 1.1);
  std::printf("rho(P^-1 Delta P) at the last state: %.4f\n", rho);

  const TaskLoss loss(scene);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  BackwardSettings settings = scene.solver.backward;
  settings.tolerance = 1e-10;
  settings.maxIterations = 200;
  settings.method = "direct";
  const GradientResult reference = backpropagate(pass.trajectory, loss, parameters, settings);
  settings.method = "fixed_point";
  const GradientResult fixedPoint = backpropagate(pass.trajectory, loss, parameters, settings);
  EXPECT_GT(fixedPoint.solver.notConverged, 0);
  EXPECT_GT(fixedPoint.solver.diverged, 0);
  EXPECT_EQ(fixedPoint.solver.fallbacks, fixedPoint.solver.notConverged);
  settings.method = "gmres";
  const GradientResult gmres = backpropagate(pass.trajectory, loss, parameters, settings);
  std::printf(
      "fixed point: %d of %d steps not converged (%d diverged), %d fallbacks; gmres: %lld "
      "iterations, "
      "max %d per step, %d fallbacks\n",
      fixedPoint.solver.notConverged, fixedPoint.solver.solves, fixedPoint.solver.diverged,
      fixedPoint.solver.fallbacks, gmres.solver.iterations, gmres.solver.maxIterations,
      gmres.solver.fallbacks);
  EXPECT_EQ(gmres.solver.fallbacks, 0);
  for (int k = 0; k < parameters.size(); ++k) {
    SCOPED_TRACE(parameters[k].path);
    EXPECT_LT(relativeError(fixedPoint.gradient[k], reference.gradient[k]), 1e-7);
    EXPECT_LT(relativeError(gmres.gradient[k], reference.gradient[k]), 1e-7);
  }
  // And that gradient is the true one.
  GradientCheckOptions options;
  options.backwardMethod = "fixed_point";  // falls back on the diverging steps
  const GradientCheckReport report = checkGradient(scene, parameters, options);
  EXPECT_GT(report.backward.fallbacks, 0);
  for (const GradientCheckEntry& e : report.entries) {
    SCOPED_TRACE(e.param);
    EXPECT_LT(e.relativeError, 1e-4) << "adjoint " << e.adjoint << " fd " << e.finiteDifference;
  }

  // Without a fallback the diverging method is a numerical failure naming the backward module.
  settings.method = "fixed_point";
  settings.fallback = "none";
  try {
    backpropagate(pass.trajectory, loss, parameters, settings);
    FAIL() << "expected a NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.module(), "backward");
  }
}

}  // namespace
}  // namespace weft
