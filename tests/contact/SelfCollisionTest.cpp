// Self-collision (node-node pairs, notes Sec. 2.4): a cloth folded onto itself by a handle and a
// cloth thrown into a corner keep every pair of nodes that may collide (not sharing a triangle,
// not mesh neighbours within the reach at rest: SelfCollisionDetector::excluded) at least the
// collision distance apart, up to a stated tolerance, and stay finite. The exclusion rule itself
// is tested on a folded strip and two stacked cloths.

#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/contact/SelfCollisionDetector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace weft {
namespace {

constexpr double kRadius = 0.012;
// How far below the collision distance a pair may end a step: a quarter of it. The contact
// frame is frozen at the start of the step, so pairs that rotate relative to each other during
// the step can come a little closer than the frozen normal allows.
constexpr double kTolerance = 0.25 * kRadius;

// Whether state n is the start or the end of a step whose solve converged.
bool convergedState(const test::ContactRun& run, int n) {
  return n == 0 || run.trajectory.steps[n - 1].converged;
}

// The smallest separation of any pair that may collide in state n, relative to its collision
// distance (1 = exactly touching; 1e9 when no pair is within it).
double closestPairRatio(const test::ContactRun& run, const SelfCollisionDetector& detector, int n) {
  const int m = run.sim->cloth().nodeCount();
  const NodeMatrix& x = run.trajectory.positions[n];
  double worst = 1e9;
  for (int a = 0; a < m; ++a)
    for (int b = a + 1; b < m; ++b) {
      const double d = (x.row(a) - x.row(b)).squaredNorm();
      const double r = detector.collisionDistance(a, b);
      if (d > r * r || detector.excluded(a, b)) continue;
      worst = std::min(worst, std::sqrt(d) / r);
    }
  return worst;
}

// The same over all states.
double closestPairRatio(const test::ContactRun& run, int& worstStep) {
  const SelfCollisionDetector detector(*run.scene, run.sim->cloth());
  double worst = 1e9;
  for (int n = 0; n < static_cast<int>(run.trajectory.positions.size()); ++n) {
    const double ratio = closestPairRatio(run, detector, n);
    if (ratio < worst) worst = ratio, worstStep = n;
  }
  return worst;
}

// Every state finite, every recorded pair on the branch it claims, and enough pairs.
void expectFiniteWithPairsOnTheirBranches(const test::ContactRun& run, const char* what) {
  for (const NodeMatrix& x : run.trajectory.positions) ASSERT_TRUE(x.allFinite()) << what;
  int pairs = 0;
  // A step split by adaptive time stepping keeps its pieces' contacts (the step's record is its
  // last piece's).
  std::vector<const StepContacts*> records;
  const Trajectory& t = run.trajectory;
  for (std::size_t n = 0; n < t.contacts.size(); ++n)
    if (n < t.substeps.size() && !t.substeps[n].empty()) {
      for (const Substep& piece : t.substeps[n]) records.push_back(&piece.contacts);
    } else {
      records.push_back(&t.contacts[n]);
    }
  for (const StepContacts* c : records)
    for (const ContactPoint& p : c->points) {
      if (p.partner < 0) continue;
      ++pairs;
      // Pairs are solved by Gauss-Seidel sweeps: their law holds to the sweep tolerance.
      ASSERT_EQ(test::branchViolation(p, 1e-3), "")
          << what << ", pair " << p.node << "-" << p.partner;
    }
  EXPECT_GT(pairs, 40) << what << ": the scene should bring the cloth into self-contact";
}

void expectFiniteAndPairsApart(const test::ContactRun& run, const char* what) {
  expectFiniteWithPairsOnTheirBranches(run, what);
  int worstStep = -1;
  const double ratio = closestPairRatio(run, worstStep);
  ::testing::Test::RecordProperty(std::string(what) + "_closest_pair_ratio", std::to_string(ratio));
  EXPECT_GT(ratio, 1.0 - kTolerance / kRadius) << what << ": at state " << worstStep;
}

TEST(SelfCollision, ClothFoldedOntoItselfKeepsItsLayersApart) {
  // A cloth on the floor; a handle lifts its +X edge over and lays it on the -X half.
  const int q = 10;
  nlohmann::json doc = test::clothScene(0.4, q, Vec3(0, 1e-3, 0), 0.01, 500.0, 1e-4, 0.2);
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.5);
  doc["cloths"][0]["self_collision"] = {{"radius", kRadius}, {"friction", 0.3}};
  std::vector<int> edge;
  for (int j = 0; j <= q; ++j) edge.push_back(j * (q + 1) + q);
  doc["cloths"][0]["attachments"] =
      nlohmann::json::array({{{"vertices", edge},
                              {"kind", "handle"},
                              {"trajectory",
                               {{"keyframes",
                                 {{{"time", 0.0}, {"offset", {0, 0, 0}}},
                                  {{"time", 0.3}, {"offset", {-0.2, 0.15, 0}}},
                                  {{"time", 0.6}, {"offset", {-0.36, 0.025, 0}}}}}}}}});
  const test::ContactRun run = test::runScene(doc, 80);
  expectFiniteAndPairsApart(run, "fold");
  // Folded: the handle edge lies over the opposite half.
  EXPECT_LT(run.trajectory.positions.back()(q, 0), -0.1);
}

// The exclusion rule (SelfCollisionDetector.h): only mesh neighbours that start within the reach
// are never paired. Two cloths stacked closer than the reach used to be excluded wholesale (their
// rest distance was below it), so a cloth lying on another had no pairs at all and sank into it.
TEST(SelfCollisionDetector, ExcludesOnlyMeshNeighboursThatStartWithinTheReach) {
  const double radius = 0.008,
               reach = (1.0 + SelfCollisionDetector::kMarginFraction) * radius;  // 12 mm
  const double gap = 0.004;  // 4 mm: within the reach
  // Cloth 0: a 0.1 m x 5 mm strip of 20 x 1 quads (5 mm edges), folded at x = 0 so that its +X half
  // lies 4 mm above its -X half (column 10 + k above column 10 - k). Cloth 1: the same strip, flat,
  // 4 mm below cloth 0's lower layer.
  nlohmann::json doc = test::gridScene(0.1, 20, 0.01, 0);
  doc["cloths"][0]["mesh"]["grid"] = {{"size", {0.1, 0.005}}, {"resolution", {20, 1}}};
  doc["cloths"][0]["self_collision"] = {{"radius", radius}, {"friction", 0.3}};
  nlohmann::json top = doc["cloths"][0];
  top["mesh"]["grid"] = {{"size", {0.1, 0.005}}, {"resolution", {20, 1}}};
  top["mesh"]["transform"] = {{"translate", {0.0, -gap, 0.0}}};
  doc["cloths"].push_back(top);
  Scene scene = test::parse(doc);
  TriangleMesh& strip = scene.cloths[0].mesh;
  for (int v = 0; v < strip.vertexCount(); ++v)
    if (strip.vertices(v, 0) > 1e-9)
      strip.vertices.row(v) = Vec3(-strip.vertices(v, 0), gap, strip.vertices(v, 2)).transpose();
  const ClothModel model = buildClothModel(scene);
  SelfCollisionDetector detector(scene, model);
  const int n = 21, second = model.vertexOffset[1];
  const auto node = [](int column) { return column; };  // row 0 of the strip (z = -2.5 mm)
  const auto restDistance = [&](int a, int b) {
    return (model.rest.vertices.row(a) - model.rest.vertices.row(b)).norm();
  };

  // Along the unfolded lower layer: 10 mm apart (two edges) is within the reach, 15 mm is not.
  EXPECT_TRUE(detector.excluded(node(0), node(1)));  // one ring
  EXPECT_TRUE(detector.excluded(node(0), node(2)));
  EXPECT_FALSE(detector.excluded(node(0), node(3)));
  // Across the fold: column 9 under column 11 (4 mm) is joined through the fold by 11.4 mm of
  // edges: neighbours. Column 0 under column 20 (4 mm) is 104 mm away along the mesh: two layers.
  ASSERT_NEAR(restDistance(node(9), node(11)), gap, 1e-12);
  ASSERT_NEAR(restDistance(node(0), node(20)), gap, 1e-12);
  EXPECT_TRUE(detector.excluded(node(9), node(11)));
  EXPECT_FALSE(detector.excluded(node(0), node(20)));
  EXPECT_FALSE(detector.excluded(node(20), node(0)));
  // Nodes of different cloths are never excluded, however close they start (cloth 1 lies 4 mm
  // under cloth 0's lower layer, node under node).
  int crossClose = 0;
  for (int a = 0; a < second; ++a)
    for (int b = second; b < model.nodeCount(); ++b) {
      ASSERT_FALSE(detector.excluded(a, b)) << a << "-" << b;
      ASSERT_FALSE(detector.excluded(b, a)) << b << "-" << a;
      if (restDistance(a, b) < reach) ++crossClose;
    }
  EXPECT_GT(crossClose, n);
  // The rule is symmetric.
  for (int a = 0; a < model.nodeCount(); ++a)
    for (int b = 0; b < model.nodeCount(); ++b)
      ASSERT_EQ(detector.excluded(a, b), detector.excluded(b, a));

  // Detection at rest (no motion) pairs the layers and the two cloths: every pair it reports is
  // within the reach and not excluded, and the two far-from-the-fold examples above are among them.
  std::vector<ContactPoint> pairs;
  detector.detect(model.rest.vertices, NodeMatrix::Zero(model.nodeCount(), 3), 0.01, pairs);
  bool layers = false, cloths = false;
  for (const ContactPoint& c : pairs) {
    EXPECT_LT(restDistance(c.node, c.partner), reach);
    EXPECT_FALSE(detector.excluded(c.node, c.partner));
    layers |= c.node == node(0) && c.partner == node(20);
    cloths |= c.node == node(0) && c.partner == second + node(0);
  }
  EXPECT_TRUE(layers) << "the folded layers were not paired";
  EXPECT_TRUE(cloths) << "the stacked cloths were not paired";
}

// Two cloths falling together, 35 mm apart, land on the floor at 5 m/s. Detection sees the
// predicted paths (DiffCloth Eq. 9): both layers move 5 cm per step in parallel, so no pair comes
// near, and only the floor contacts are found. On the landing step the floor stops the lower
// layer and the upper one comes down onto it, stopped only by the floor too (3 mm above the lower
// layer, and then bouncing), unless the step's solved path is checked and the pairs it meets are
// added (FrictionalContact::addMissedContacts; stats.csv's late_contacts). Run with the PD
// iteration and with the Newton contact solve.
TEST(SelfCollision, StackedClothsLandingTogetherStayStacked) {
  for (const char* method : {"pd", "newton"}) {
    SCOPED_TRACE(method);
    nlohmann::json doc = test::clothScene(0.2, 6, Vec3(0, 0.02, 0), 0.01, 300.0, 1e-4, 0.2);
    doc["cloths"][0]["initial_velocity"] = {0.0, -5.0, 0.0};
    doc["cloths"][0]["self_collision"] = {{"radius", kRadius}, {"friction", 0.3}};
    nlohmann::json upper = doc["cloths"][0];
    upper["mesh"]["transform"]["translate"] = {0.0, 0.055, 0.0};
    doc["cloths"].push_back(upper);
    test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.3);
    doc["solver"]["contact"] = method;
    const test::ContactRun run = test::runScene(doc, 15);
    const Trajectory& t = run.trajectory;
    int late = 0;
    for (const StepStats& s : t.steps) late += s.lateContacts;
    EXPECT_GT(late, 0) << "the scene no longer makes detection miss the landing pairs";
    const int m = run.sim->cloth().nodeCount() / 2;  // lower cloth: nodes 0..m-1, upper: m..2m-1
    for (int n = 1; n <= t.stepCount(); ++n) {
      ASSERT_TRUE(t.positions[n].allFinite()) << "state " << n;
      // Every upper node above its lower twin by at least the collision distance, less the
      // tolerance of the tests above.
      const double above =
          (t.positions[n].col(1).tail(m) - t.positions[n].col(1).head(m)).minCoeff();
      EXPECT_GT(above, kRadius - kTolerance) << "state " << n;
    }
    // Landed: both layers at rest on the floor, the lower within its 1 mm skin.
    EXPECT_LT(t.positions.back().col(1).head(m).maxCoeff(), 2e-3);
    EXPECT_LT(test::maxSpeedOf(t.velocities.back()), 0.05);
  }
}

// A cloth thrown into the corner of the floor and two walls, crumpling onto itself, with the
// Newton contact solve (set below) and the default adaptive time stepping. The converged steps
// hold the walls: that needed the Newton matrix to differentiate coupled contacts (corner nodes,
// pairs sharing nodes) through the fixed point of their sweeps (ContactSolver::addLawJacobian).
// The scene starts 9.3 mm across the x = -0.2 wall, so the walls are checked from state 1 on
// (and that it still starts across).
TEST(SelfCollision, ClothCrumpledIntoACornerKeepsNodesApart) {
  // Where the crumpling cloth goes depends on rounding (a change of the preconditioner's
  // ordering alone moves every run), so the scene is run three times, its initial velocity
  // differing by 1e-7 relative, and judged over the three: every state finite and every recorded
  // pair on its branch, every one of the 240 steps converged (at the scene's dt alone, without
  // halving, 202 did), the walls held and no pair closer than 0.75 of its distance. What each
  // run did is printed.
  int converged = 0, closeStates = 0;
  for (int variant = 0; variant < 3; ++variant) {
    SCOPED_TRACE("run " + std::to_string(variant));
    nlohmann::json doc = test::clothScene(0.5, 12, Vec3(0.05, 0.25, 0.05), 0.01, 300.0, 1e-4, 0.2);
    doc["cloths"][0]["mesh"]["transform"]["rotate_deg"] = {20, 0, 30};
    doc["cloths"][0]["initial_velocity"] = {-1.5 * (1.0 + 1e-7 * variant), -1.0, -1.5};
    doc["cloths"][0]["self_collision"] = {{"radius", kRadius}, {"friction", 0.3}};
    test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.4);
    test::addObstacle(doc, "plane", {{"point", {-0.2, 0, 0}}, {"normal", {1, 0, 0}}}, 0.4);
    test::addObstacle(doc, "plane", {{"point", {0, 0, -0.2}}, {"normal", {0, 0, 1}}}, 0.4);
    doc["solver"]["contact"] = "newton";
    const test::ContactRun run = test::runScene(doc, 80);
    int runConverged = 0;
    for (const StepStats& s : run.trajectory.steps) runConverged += s.converged;
    converged += runConverged;
    expectFiniteWithPairsOnTheirBranches(run, "corner");
    // Held by the walls and the floor (1 mm skin each), within a millimetre, from the first step
    // on: the tilted cloth starts with a corner 9.3 mm across the x = -0.2 wall (state 0), which
    // the first step's contact pushes back out.
    const Trajectory& t = run.trajectory;
    ASSERT_LT(t.positions.front().col(0).minCoeff(), -0.2)
        << "the scene no longer starts across the wall";
    const SelfCollisionDetector detector(*run.scene, run.sim->cloth());
    double deepest = 0.0, closest = 1e9;  // over all states: past a wall's plane (m), pair ratio
    std::string close;
    for (int n = 1; n <= t.stepCount(); ++n) {
      const NodeMatrix& x = t.positions[n];
      const double inside =
          -std::min({x.col(0).minCoeff() + 0.2, x.col(1).minCoeff(), x.col(2).minCoeff() + 0.2});
      const double ratio = closestPairRatio(run, detector, n);
      deepest = std::max(deepest, inside);
      closest = std::min(closest, ratio);
      if (!convergedState(run, n)) continue;
      EXPECT_LE(inside, 0.0) << "state " << n;
      if (ratio < 1.0 - kTolerance / kRadius) {
        ++closeStates;
        close += " " + std::to_string(n) + " (" + std::to_string(ratio) + ")";
      }
    }
    std::printf(
        "corner run %d: %d of 80 steps converged; converged states with a pair too close:%s; over "
        "all "
        "steps, deepest inside a wall %.2f mm, closest pair %.2f of its distance\n",
        variant, runConverged, close.empty() ? " none" : close.c_str(), 1e3 * deepest, closest);
  }
  EXPECT_EQ(converged, 240) << "of 240 steps";
  EXPECT_EQ(closeStates, 0);
}

}  // namespace
}  // namespace weft
