// The vertex inspector and the contact plots read what the simulator recorded: the cached
// frame's position, velocity and contacts of a vertex are those of the engine's own trajectory,
// forces are impulses over the time step, and the per-step series follow StepStats.

#include <SimulationCache.h>
#include <StepStatsSeries.h>
#include <VertexInspector.h>

#include "support/SceneBuilder.h"

#include <weft/physics/Simulator.h>

#include <gtest/gtest.h>

namespace weft::editor {
namespace {

// A 0.6 m cloth of 8 x 8 quads dropped from just above a sphere: its centre lands on top.
nlohmann::json dropOnSphere(int steps) {
  nlohmann::json doc = test::gridScene(0.6, 8, 0.01, steps, 300.0, 1e-4, 0.2);
  doc["gravity"] = {0.0, -9.8, 0.0};
  doc["solver"] = {{"pd_iterations", 300}, {"pd_tolerance", 1e-6}};
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 0.205, 0.0}}};
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.2}}}, {"friction", 0.4}}};
  return doc;
}

constexpr int kCentre = 4 * 9 + 4;

TEST(VertexInspector, ReportsTheTrajectoryOfTheSimulator) {
  const int steps = 12;
  const auto scene = std::make_shared<const Scene>(test::parse(dropOnSphere(steps)));
  SimulationCache cache;
  cache.start(scene, steps);
  cache.wait();
  ASSERT_EQ(cache.status(), SimulationCache::Status::Done) << cache.error();

  Simulator simulator(*scene);
  Trajectory own;
  simulator.run(steps, own);
  ASSERT_EQ(own.contacts.size(), std::size_t(steps));

  bool sawContact = false;
  for (int k = 1; k <= steps; ++k) {
    SCOPED_TRACE("state " + std::to_string(k));
    const auto frame = cache.frame(k);
    ASSERT_TRUE(frame);
    const auto r = inspectVertex(*frame, kCentre, scene->time.dt, {0, 81});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->state, k);
    EXPECT_EQ(r->cloth, 0);
    EXPECT_EQ(r->localVertex, kCentre);
    // The worker may run another OpenMP thread count than this test: agreement to rounding.
    EXPECT_LT((r->position - own.positions[k].row(kCentre).transpose()).norm(), 1e-9);
    EXPECT_LT((r->velocity - own.velocities[k].row(kCentre).transpose()).norm(), 1e-7);
    std::vector<const ContactPoint*> expected;
    for (const ContactPoint& p : own.contacts[k - 1].points)
      if (p.node == kCentre || p.partner == kCentre) expected.push_back(&p);
    ASSERT_EQ(r->contacts.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const VertexContact& c = r->contacts[i];
      EXPECT_EQ(c.branch, expected[i]->branch);
      EXPECT_EQ(c.obstacle, expected[i]->obstacle);
      EXPECT_LT((c.impulse - expected[i]->impulse).norm(), 1e-9);
      EXPECT_LT((c.force - expected[i]->impulse / scene->time.dt).norm(), 1e-7);
      EXPECT_EQ(c.friction, 0.4);
    }
    if (!expected.empty()) {
      EXPECT_NE(r->branch, ContactBranch::None) << "the overlay colours a contact vertex";
      if (r->branch == ContactBranch::Stick || r->branch == ContactBranch::Slip) {
        sawContact = true;
        EXPECT_GT(r->contactForce.y(), 0.0) << "the sphere pushes the cloth up";
      } else {
        EXPECT_EQ(r->contactForce, Vec3::Zero()) << "taking off: no force";
      }
    }
  }
  EXPECT_TRUE(sawContact) << "the centre presses on the sphere within " << steps << " steps";

  // The arrows: the total force per node, as contact_forces.npy has it.
  const auto last = cache.frame(steps);
  const std::vector<Vec3> forces = nodeContactForces(last->contacts, 81, scene->time.dt);
  ASSERT_EQ(forces.size(), 81u);
  const auto centre = inspectVertex(*last, kCentre, scene->time.dt, {0, 81});
  EXPECT_LT((forces[kCentre] - centre->contactForce).norm(), 1e-12);
  EXPECT_FALSE(inspectVertex(*last, 81, scene->time.dt, {0, 81})) << "no such vertex";
  EXPECT_FALSE(inspectVertex(*last, -1, scene->time.dt, {0, 81}));
}

TEST(VertexInspector, PairContactsAreSeenFromEitherEnd) {
  CachedFrame frame;
  frame.state = 3;
  frame.positions = NodeMatrix::Zero(4, 3);
  frame.velocities = NodeMatrix::Zero(4, 3);
  ContactPoint pair;
  pair.node = 1;
  pair.partner = 2;
  pair.branch = ContactBranch::Stick;
  pair.normal = Vec3(0, 1, 0);
  pair.impulse = Vec3(0, 0.02, 0);
  frame.contacts.points.push_back(pair);
  const auto a = inspectVertex(frame, 1, 0.01, {0, 4});
  const auto b = inspectVertex(frame, 2, 0.01, {0, 4});
  ASSERT_TRUE(a && b);
  ASSERT_EQ(b->contacts.size(), 1u);
  EXPECT_EQ(a->contacts[0].partner, 2);
  EXPECT_EQ(b->contacts[0].partner, 1);
  EXPECT_TRUE(a->contactForce.isApprox(Vec3(0, 2, 0)));
  EXPECT_TRUE(b->contactForce.isApprox(Vec3(0, -2, 0)));
  EXPECT_TRUE(b->contacts[0].normal.isApprox(Vec3(0, -1, 0)));
  const std::vector<Vec3> forces = nodeContactForces(frame.contacts, 4, 0.01);
  EXPECT_TRUE(forces[1].isApprox(Vec3(0, 2, 0)));
  EXPECT_TRUE(forces[2].isApprox(Vec3(0, -2, 0)));
  EXPECT_TRUE(forces[0].isZero());
}

TEST(StepStatsSeries, FollowsTheCachedStepsAndRestartsWithARun) {
  const int steps = 10;
  const auto scene = std::make_shared<const Scene>(test::parse(dropOnSphere(steps)));
  SimulationCache cache;
  StepStatsSeries series;
  series.update(cache);
  EXPECT_EQ(series.size(), 0);
  cache.start(scene, steps);
  cache.wait();
  series.update(cache);
  ASSERT_EQ(series.size(), steps);
  std::vector<int> unconverged;
  for (int k = 1; k <= steps; ++k) {
    const StepStats& s = cache.frame(k)->stats;
    if (!s.converged) unconverged.push_back(k);
    EXPECT_EQ(series.takeoff()[std::size_t(k - 1)], float(s.takeoff));
    EXPECT_EQ(series.stick()[std::size_t(k - 1)], float(s.stick));
    EXPECT_EQ(series.slip()[std::size_t(k - 1)], float(s.slip));
    EXPECT_EQ(series.pdIterations()[std::size_t(k - 1)], float(s.pdIterations));
  }
  EXPECT_TRUE(series.anyContact());
  EXPECT_EQ(series.unconvergedStates(), unconverged);
  series.update(cache);
  EXPECT_EQ(series.size(), steps) << "no frame is appended twice";
  // A new run, capped at one iteration per step against a tolerance none reaches.
  Scene capped = test::parse(dropOnSphere(steps));
  capped.solver.pdIterations = 1;
  capped.solver.pdTolerance = 1e-14;
  cache.start(std::make_shared<const Scene>(capped), 3);
  cache.wait();
  series.update(cache);
  EXPECT_EQ(series.size(), 3) << "a new run starts a new series";
  EXPECT_EQ(series.unconvergedStates(), (std::vector<int>{1, 2, 3}));
}

}  // namespace
}  // namespace weft::editor
