// Hard contact cases (spec: "hard cases stay numerically stable"): a 20 m/s impact on a plane
// and on a 1 cm plate (no tunnelling), a cloth squeezed between two obstacles (nodes in two
// contacts at once), and kinematic obstacles (a box, a cylinder) pushing a cloth across the floor.

#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/contact/ObstacleContactDetector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace weft {
namespace {

constexpr double kSkin = 1e-3, kTolerance = 1e-3;

TEST(HardContact, FastImpactOnAPlaneDoesNotTunnel) {
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0, 0.25, 0), 0.01, 1000.0);
  doc["cloths"][0]["initial_velocity"] = {0.0, -20.0, 0.0};
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.3);
  const test::ContactRun run = test::runScene(doc, 30);
  for (const NodeMatrix& x : run.trajectory.positions) {
    ASSERT_TRUE(x.allFinite());
    ASSERT_GT(x.col(1).minCoeff(), kSkin - kTolerance);
  }
  // Stopped by the plane: inelastic contact, no bounce.
  EXPECT_LT(test::maxSpeedOf(run.trajectory.velocities.back()), 0.5);
  EXPECT_LT(run.trajectory.positions.back().col(1).maxCoeff(), 0.01);
}

TEST(HardContact, FastImpactOnAThinPlateDoesNotTunnel) {
  // A 1 cm plate: a node moves 20 cm per step, twenty times the plate's thickness.
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0, 0.25, 0), 0.01, 1000.0);
  doc["cloths"][0]["initial_velocity"] = {0.0, -20.0, 0.0};
  test::addObstacle(doc, "box", {{"center", {0, 0, 0}}, {"size", {1.0, 0.01, 1.0}}}, 0.3);
  const test::ContactRun run = test::runScene(doc, 30);
  for (const NodeMatrix& x : run.trajectory.positions) {
    ASSERT_TRUE(x.allFinite());
    ASSERT_GT(x.col(1).minCoeff(), 0.005 + kSkin - kTolerance)
        << "a node went into or through the plate";
  }
}

TEST(HardContact, ClothSqueezedBetweenTwoObstacles) {
  // A slab comes down onto a cloth on the floor until the gap is 2 mm (the two skins touch),
  // then slides sideways: with friction on both sides the cloth is held and dragged half way.
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0, kSkin, 0), 0.01, 1000.0);
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.5);
  test::addObstacle(doc, "box", {{"center", {0, 0.1, 0}}, {"size", {1.0, 0.1, 1.0}}}, 0.5);
  doc["obstacles"][1]["motion"] = {{"keyframes",
                                    {{{"time", 0.0}, {"offset", {0, 0, 0}}},
                                     {{"time", 0.2}, {"offset", {0, -0.048, 0}}},
                                     {{"time", 0.3}, {"offset", {0, -0.048, 0}}},
                                     {{"time", 0.6}, {"offset", {0.1, -0.048, 0}}}}}};
  const test::ContactRun run = test::runScene(doc, 60);
  int doubleContacts = 0;
  for (int n = 1; n <= run.trajectory.stepCount(); ++n) {
    const NodeMatrix& x = run.trajectory.positions[n];
    ASSERT_TRUE(x.allFinite());
    ASSERT_GT(x.col(1).minCoeff(), kSkin - kTolerance) << "step " << n;
    const double ceiling = n >= 20 ? 0.002 : 0.05 - 0.048 * n / 20.0;
    ASSERT_LT(x.col(1).maxCoeff(), ceiling - kSkin + kTolerance) << "step " << n;
    std::vector<int> perNode(x.rows(), 0);
    for (const ContactPoint& p : run.trajectory.contacts[n - 1].points) {
      ASSERT_EQ(test::branchViolation(p, 1e-3), "") << "step " << n;
      if (p.branch != ContactBranch::TakeOff) ++perNode[p.node];
    }
    for (int c : perNode) doubleContacts += c == 2;
  }
  EXPECT_GT(doubleContacts, 100) << "nodes should be pressed by both obstacles at once";
  // Dragged along by the slab's friction against the floor's: both have mu 0.5 and the floor's
  // normal force is the slab's plus the weight, so the cloth moves, but not faster than the slab.
  const double shift = run.trajectory.positions.back().col(0).mean() -
                       run.trajectory.positions.front().col(0).mean();
  RecordProperty("squeezed_shift_mm", std::to_string(shift * 1e3));
  EXPECT_GT(shift, -1e-3);
  EXPECT_LT(shift, 0.1 + 1e-3);
}

// A kinematic obstacle standing on the floor (the plane y = 0) sweeps across it at 1 m/s for
// 0.4 s into a cloth lying there. For each contact solve: every node below the obstacle's top
// (y < 0.1) stays outside it by more than that solve's bound, where outside(step, node position)
// is the node's signed distance to the obstacle's moving surface), and the cloth moves on by more
// than minimumShift; the closest approach and the shift are recorded as test properties.
void expectObstaclePushesTheCloth(const char* kind, const nlohmann::json& shape,
                                  const std::function<double(int, const Vec3&)>& outside,
                                  const std::vector<std::pair<const char*, double>>& boundPerMethod,
                                  double minimumShift) {
  nlohmann::json doc = test::clothScene(0.3, 10, Vec3(0, kSkin, 0), 0.01, 1000.0);
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.2);
  test::addObstacle(doc, kind, shape, 0.2);
  doc["obstacles"][1]["motion"] = {
      {"keyframes",
       {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.4}, {"offset", {0.4, 0, 0}}}}}};
  for (const auto& [method, bound] : boundPerMethod) {
    SCOPED_TRACE(method);
    doc["solver"]["contact"] = method;
    const test::ContactRun run = test::runScene(doc, 40);
    double closest = 1.0;
    for (int n = 1; n <= run.trajectory.stepCount(); ++n) {
      const NodeMatrix& x = run.trajectory.positions[n];
      ASSERT_TRUE(x.allFinite());
      for (int i = 0; i < x.rows(); ++i)
        if (x(i, 1) < 0.1) {  // unless it rode up over the top
          const double d = outside(n, x.row(i).transpose());
          ASSERT_GT(d, bound) << "step " << n << " node " << i;
          closest = std::min(closest, d);
        }
    }
    const double shift = run.trajectory.positions.back().col(0).mean() -
                         run.trajectory.positions.front().col(0).mean();
    ::testing::Test::RecordProperty(std::string("pushed_shift_mm_") + method,
                                    std::to_string(shift * 1e3));
    ::testing::Test::RecordProperty(std::string("closest_mm_") + method,
                                    std::to_string(closest * 1e3));
    EXPECT_GT(shift, minimumShift);
  }
}

// The box stands on the floor: its bottom face is flush with the floor plane, so a node lying on
// the floor (in the floor's 1 mm skin) is 1 mm from the box's bottom face and, once the wall has
// moved over it within a step, farther from the side face. The nearest-face normal (-y) pressed
// such a node into the floor and let the wall pass over it (node 0 ended 2.2 mm behind the wall
// at step 9); detection now gives it the face it entered through (BoxShape::sampleMoved). Both
// contact solves (the rule is detection's, not the solve's).
TEST(HardContact, MovingObstaclePushesTheCloth) {
  // The wall's face is at x = -0.2 + v t.
  expectObstaclePushesTheCloth(
      "box", {{"center", {-0.3, 0.05, 0}}, {"size", {0.2, 0.1, 0.6}}},
      [](int n, const Vec3& x) { return x.x() - (-0.2 + 1.0 * n * 0.01); },
      {{"pd", kSkin - 3 * kTolerance}, {"newton", kSkin - 3 * kTolerance}}, 0.15);
}

// The same with a cylinder standing on the floor (its bottom cap flush with it), which sweeps
// over the cloth with its round side: the nodes it reaches are nearer its bottom cap than its
// side and get the side's normal only through CylinderShape::sampleMoved. Measured: the Newton
// contact solve keeps every node in the skin (closest 1.0 mm outside); the PD solve, on this
// stiff cloth pressed into the cylinder's curve, stops at pd_iterations on some steps with nodes
// up to 3.8 mm inside (its known limitation, docs/how-it-works/contact.md). With the
// nearest-surface rule nodes ended 99 mm inside and the cloth moved 0.11 m instead of 0.35.
TEST(HardContact, MovingCylinderPushesTheCloth) {
  const double radius = 0.1;
  expectObstaclePushesTheCloth(
      "cylinder", {{"a", {-0.3, 0.0, 0}}, {"b", {-0.3, 0.1, 0}}, {"radius", radius}},
      [&](int n, const Vec3& x) {
        return std::hypot(x.x() - (-0.3 + 1.0 * n * 0.01), x.z()) - radius;
      },
      {{"pd", -5e-3}, {"newton", kSkin - 3 * kTolerance}}, 0.3);
}

// The detection rule behind it, for one step: the wall (face at x = -0.15 at t = 0.05, -0.14 at
// t = 0.06) moves over a node lying on the floor 1 mm ahead of it. At the end-of-step pose the
// node is 9 mm inside the box and 1 mm above its bottom face; it came in through the side, so
// the contact is the side's: normal +x, and the reference velocity brings it to the face's skin
// by the end of the step (gap -10 mm over 10 ms: 1 m/s along +x).
TEST(HardContact, NodeTheWallMovesOverGetsTheWallsNormal) {
  nlohmann::json doc = test::clothScene(0.3, 2, Vec3(0, kSkin, 0), 0.01, 1000.0);
  test::addObstacle(doc, "plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}, 0.2);
  test::addObstacle(doc, "box", {{"center", {-0.3, 0.05, 0}}, {"size", {0.2, 0.1, 0.6}}}, 0.2);
  doc["obstacles"][1]["motion"] = {
      {"keyframes",
       {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.4}, {"offset", {0.4, 0, 0}}}}}};
  const Scene scene = test::parse(doc);
  std::vector<ContactObstacle> obstacles;
  for (const Obstacle& o : scene.obstacles) obstacles.emplace_back(o, makeObstacleShape(o));
  for (ContactObstacle& o : obstacles) o.beginStep(0.05, 0.06);
  NodeMatrix x(2, 3);
  x.row(0) = Vec3(-0.149, kSkin, 0.1).transpose();  // the node the wall reaches
  x.row(1) = Vec3(0.1, kSkin, 0.1).transpose();     // on the floor only
  ObstacleContactDetector detector(obstacles, 2e-3);
  std::vector<ContactPoint> contacts;
  detector.detect(x, NodeMatrix::Zero(2, 3), 0.01, contacts);
  ASSERT_EQ(contacts.size(), 3u);
  EXPECT_EQ(contacts[0].node, 0);
  EXPECT_EQ(contacts[0].obstacle, 0);
  const ContactPoint& wall = contacts[1];
  ASSERT_EQ(wall.node, 0);
  ASSERT_EQ(wall.obstacle, 1);
  EXPECT_LT((wall.normal - Vec3::UnitX()).norm(), 1e-12) << wall.normal.transpose();
  EXPECT_LT((wall.reference - Vec3(1.0, 0, 0)).norm(), 1e-9) << wall.reference.transpose();
  EXPECT_EQ(contacts[2].node, 1);
  EXPECT_EQ(contacts[2].obstacle, 0);
}

}  // namespace
}  // namespace weft
