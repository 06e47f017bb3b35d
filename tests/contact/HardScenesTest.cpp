// Hard contact scenes solved with the default contact solve (Newton with adaptive time stepping,
// solver.max_halvings) at the default tolerance, 1e-4 m/s^2: every step must converge and no
// node of a converged step may end deeper than 0.1 mm inside an obstacle's skin; each scene also
// asserts what it is about physically. After issue 36: a cloth on a spinning sphere, a cloth
// pulled across a table edge at 0.5, 2 and 8 m/s (C-IPC's table-cloth pull), a cloth thrown
// into a corner at 20 m/s, three cloths stacked and dropped on a floor, and a cloth squeezed
// between a floor and a slab to less than twice the skin.

#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/physics/Model.h>
#include <weft/record/ConvergenceReport.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace weft {
namespace {

constexpr double kSkin = 1e-3;
constexpr double kPi = 3.14159265358979323846;

// Every step converged at the scene's tolerance, none deeper than 0.1 mm inside a skin; prints
// how the run was solved.
void expectSolved(const test::ContactRun& run, const std::string& name) {
  int converged = 0, split = 0, deepestHalvings = 0;
  double depth = 0.0;
  for (const StepStats& s : run.trajectory.steps) {
    converged += s.converged;
    split += s.substeps > 1;
    deepestHalvings = std::max(deepestHalvings, s.halvings);
    depth = std::max(depth, s.depth);
    EXPECT_TRUE(s.converged) << name << ": step " << s.step << " residual " << s.residual;
    EXPECT_LE(s.depth, ConvergenceReport::kDepthTolerance) << name << ": step " << s.step;
  }
  for (const NodeMatrix& x : run.trajectory.positions) ASSERT_TRUE(x.allFinite());
  std::printf("%s: %d of %d steps converged, %d split (down to dt/%d), deepest %.4f mm\n",
              name.c_str(), converged, run.trajectory.stepCount(), split, 1 << deepestHalvings,
              1e3 * depth);
}

// The mean angle (rad, about +y through the origin) the cloth turned between two states.
double turnedAngle(const NodeMatrix& a, const NodeMatrix& b) {
  double sum = 0.0;
  int counted = 0;
  for (int i = 0; i < a.rows(); ++i) {
    if (std::hypot(a(i, 0), a(i, 2)) < 0.03) continue;  // near the axis the angle is noise
    double d = std::atan2(-b(i, 2), b(i, 0)) - std::atan2(-a(i, 2), a(i, 0));
    while (d > kPi) d -= 2 * kPi;
    while (d < -kPi) d += 2 * kPi;
    sum += d;
    ++counted;
  }
  return sum / counted;
}

TEST(HardScenes, FrictionTurnsAClothWithASpinningSphere) {
  // A 0.2 m cloth on top of a 0.3 m sphere turning 90 degrees per second about +y for 1 s.
  // Sticking friction carries the cloth round with the sphere; without friction nothing acts
  // on it tangentially and it stays put.
  for (const double mu : {0.8, 0.0}) {
    nlohmann::json doc = test::clothScene(0.2, 8, Vec3(0, 0.3 + kSkin, 0), 0.01);
    doc["solver"] = nlohmann::json::object();  // the defaults
    test::addObstacle(doc, "sphere", {{"center", {0, 0, 0}}, {"radius", 0.3}}, mu);
    doc["obstacles"][0]["motion"] = {
        {"rotate", {{"center", {0, 0, 0}}, {"axis", {0, 1, 0}}, {"degrees_per_second", 90.0}}}};
    const test::ContactRun run = test::runScene(doc, 100);
    expectSolved(run, "spinning sphere mu " + std::to_string(mu));
    const double turned =
        turnedAngle(run.trajectory.positions.front(), run.trajectory.positions.back()) * 180.0 /
        kPi;
    std::printf("mu %.1f: the cloth turned %.2f degrees (the sphere 90)\n", mu, turned);
    if (mu > 0.0) {
      EXPECT_GT(turned, 80.0);
      EXPECT_LT(turned, 91.0);
    } else {
      EXPECT_LT(std::abs(turned), 1.0);
    }
  }
}

// The vertices of the cloth's +x edge, from its compiled rest state.
std::vector<int> edgeVertices(const nlohmann::json& doc) {
  const auto model = Model::compile(test::parse(doc));
  const NodeMatrix& x = model->cloth().rest.vertices;
  const double edge = x.col(0).maxCoeff();
  std::vector<int> out;
  for (int i = 0; i < x.rows(); ++i)
    if (x(i, 0) > edge - 1e-9) out.push_back(i);
  return out;
}

TEST(HardScenes, ClothPulledAcrossATableEdge) {
  // C-IPC's table-cloth pull: a 0.4 m cloth lies on a table (a box whose top is y = 0 and whose
  // edge is x = 0.3) hanging 5 cm over the edge; its overhanging edge is pulled 0.4 m away and
  // down at 0.5, 2 and 8 m/s, dragging the rest across the table top and over the edge.
  for (const double speed : {0.5, 2.0, 8.0}) {
    nlohmann::json doc = test::clothScene(0.4, 10, Vec3(0.15, kSkin, 0), 0.005);
    doc["solver"] = nlohmann::json::object();
    test::addObstacle(doc, "box", {{"center", {0, -0.05, 0}}, {"size", {0.6, 0.1, 0.6}}}, 0.4);
    const double duration = 0.4 / speed;
    const int steps = static_cast<int>(std::lround(duration / 0.005)) + 10;
    doc["cloths"][0]["attachments"] = {
        {{"vertices", edgeVertices(doc)},
         {"kind", "handle"},
         {"stiffness", 1e4},
         {"trajectory",
          {{"keyframes",
            {{{"time", 0.0}, {"offset", {0, 0, 0}}},
             {{"time", duration}, {"offset", {0.32, -0.24, 0}}}}}}}}};
    const test::ContactRun run = test::runScene(doc, steps);
    const std::string name = "table pull at " + std::to_string(speed) + " m/s";
    expectSolved(run, name);
    const NodeMatrix& start = run.trajectory.positions.front();
    const NodeMatrix& end = run.trajectory.positions.back();
    // The whole cloth came along: its trailing edge (x = -0.05 at rest) was dragged towards
    // and over the table edge.
    const double trailing = end.col(0).minCoeff() - start.col(0).minCoeff();
    std::printf("%s: trailing edge moved %.3f m\n", name.c_str(), trailing);
    EXPECT_GT(trailing, 0.2) << name;
    // And nothing went through the table: every node over the table top is above it.
    for (const NodeMatrix& x : run.trajectory.positions)
      for (int i = 0; i < x.rows(); ++i)
        if (std::abs(x(i, 0)) < 0.3 - 1e-3 && std::abs(x(i, 2)) < 0.3 - 1e-3) {
          ASSERT_GT(x(i, 1), -1e-4) << name << ": node " << i << " inside the table";
        }
  }
}

TEST(HardScenes, ClothThrownIntoACornerAtTwentyMetresPerSecond) {
  // A 0.3 m cloth with self-collision thrown at 20 m/s into the corner of a floor and two walls:
  // 10 cm per step at dt 5 ms, 30 times the skin. It must stop there, held by all three.
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0.15, 0.3, 0.15), 0.005, 1000.0, 1e-3, 0.2);
  doc["solver"] = nlohmann::json::object();
  const double v = 20.0 / std::sqrt(3.0);
  doc["cloths"][0]["initial_velocity"] = {-v, -v, -v};
  doc["cloths"][0]["self_collision"] = {{"radius", 0.005}, {"friction", 0.3}};
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.4);
  test::addObstacle(doc, "plane", {{"point", {-0.2, 0, 0}}, {"normal", {1, 0, 0}}}, 0.4);
  test::addObstacle(doc, "plane", {{"point", {0, 0, -0.2}}, {"normal", {0, 0, 1}}}, 0.4);
  const test::ContactRun run = test::runScene(doc, 60);
  expectSolved(run, "corner throw");
  for (const NodeMatrix& x : run.trajectory.positions) {
    ASSERT_GT(x.col(1).minCoeff(), -1e-4);
    ASSERT_GT(x.col(0).minCoeff(), -0.2 - 1e-4);
    ASSERT_GT(x.col(2).minCoeff(), -0.2 - 1e-4);
  }
  // Inelastic contact: the throw's kinetic energy is gone. The RMS speed falls from 20 m/s to
  // below 2 m/s (99 % of the energy dissipated); what is left is the crumpled cloth springing
  // back from the corner on its own elasticity (1.3 m/s outwards on average when this was
  // written), not a bounce off the walls, which would return most of the 20 m/s.
  const NodeMatrix& end = run.trajectory.velocities.back();
  const double rms = std::sqrt(end.rowwise().squaredNorm().mean());
  const double outwards = end.colwise().mean().dot(Vec3(1, 1, 1).normalized().transpose());
  std::printf("corner throw: final RMS speed %.3f m/s, mean outward speed %.3f m/s\n", rms,
              outwards);
  EXPECT_LT(rms, 2.0);
  EXPECT_LT(outwards, 2.0);
}

TEST(HardScenes, ThreeStackedClothsDroppedOnAFloor) {
  // Three 0.2 m cloths, 2 cm apart, falling together from 5 cm onto a floor: the bottom one
  // lands first and the others come down on it. Node-node contact (self_collision, radius
  // 8 mm) between the layers; the grids are aligned, so every node has its twin in the next
  // layer. The stack must keep its order with each layer at least the collision distance (less
  // the quarter the frozen frames allow, SelfCollisionTest's tolerance) above the one below, and
  // come to rest on the floor.
  constexpr double kRadius = 0.008;
  constexpr int kLayers = 3;
  nlohmann::json doc = test::clothScene(0.2, 8, Vec3(0, 0.05, 0), 0.005, 300.0, 1e-4, 0.2);
  doc["solver"] = nlohmann::json::object();
  doc["cloths"][0]["self_collision"] = {{"radius", kRadius}, {"friction", 0.3}};
  for (int layer = 1; layer < kLayers; ++layer) {
    nlohmann::json cloth = doc["cloths"][0];
    cloth["mesh"]["transform"]["translate"] = {0.0, 0.05 + 0.02 * layer, 0.0};
    doc["cloths"].push_back(cloth);
  }
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.4);
  const test::ContactRun run = test::runScene(doc, 120);
  expectSolved(run, "three stacked cloths");
  const Trajectory& t = run.trajectory;
  const int m = run.sim->cloth().nodeCount() / kLayers;  // layer k: nodes k m .. (k + 1) m - 1
  double closest = 1e9;
  for (int n = 1; n <= t.stepCount(); ++n)
    for (int layer = 1; layer < kLayers; ++layer) {
      const double above = (t.positions[n].col(1).segment(layer * m, m) -
                            t.positions[n].col(1).segment((layer - 1) * m, m))
                               .minCoeff();
      closest = std::min(closest, above);
      ASSERT_GT(above, 0.75 * kRadius) << "state " << n << ", layer " << layer;
    }
  // At rest: the bottom layer within its 1 mm skin of the floor, nothing moving, the stack
  // about one collision distance per layer high.
  const NodeMatrix& x = t.positions.back();
  std::printf("three stacked cloths: closest layers %.2f mm apart, top layer at %.2f mm\n",
              1e3 * closest, 1e3 * x.col(1).tail(m).maxCoeff());
  EXPECT_LT(x.col(1).head(m).maxCoeff(), 2e-3);
  EXPECT_LT(x.col(1).tail(m).maxCoeff(), 2e-3 + (kLayers - 1) * 1.5 * kRadius);
  EXPECT_LT(test::maxSpeedOf(t.velocities.back()), 0.05);
}

TEST(HardScenes, ClothSqueezedToLessThanTwiceTheSkin) {
  // A slab comes down onto a cloth lying on the floor until the gap is 1.5 mm, less than the two
  // 1 mm skins: no state keeps a node outside both, so the law cannot hold everywhere. The
  // solve must stay finite and keep the cloth between the two surfaces (neither pushed through
  // the floor nor left inside the slab); how many steps converge is printed.
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0, kSkin, 0), 0.01);
  doc["solver"] = nlohmann::json::object();
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.5);
  test::addObstacle(doc, "box", {{"center", {0, 0.1, 0}}, {"size", {1.0, 0.1, 1.0}}}, 0.5);
  doc["obstacles"][1]["motion"] = {
      {"keyframes",
       {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.2}, {"offset", {0, -0.0485, 0}}}}}};
  const test::ContactRun run = test::runScene(doc, 30);
  int converged = 0;
  for (const StepStats& s : run.trajectory.steps) converged += s.converged;
  for (int n = 0; n <= run.trajectory.stepCount(); ++n) {
    const NodeMatrix& x = run.trajectory.positions[n];
    ASSERT_TRUE(x.allFinite());
    const double slabBottom = n >= 20 ? 0.0015 : 0.05 - 0.0485 * n / 20.0;
    EXPECT_GT(x.col(1).minCoeff(), -1e-4) << "state " << n << ": through the floor";
    EXPECT_LT(x.col(1).maxCoeff(), slabBottom + 1e-4) << "state " << n << ": inside the slab";
  }
  std::printf("squeezed to 1.5 mm: %d of %d steps converged\n", converged,
              run.trajectory.stepCount());
}

}  // namespace
}  // namespace weft
