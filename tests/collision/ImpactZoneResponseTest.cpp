// The simulator's impact-zone response seen from outside (ImpactZoneResponse::setObserver,
// Simulator::impactZoneResponse): the observer gets every response's zones, consistent with the
// step's stats and with the positions the step ends at, and observing changes nothing.

#include <weft/collision/ImpactZoneResponse.h>
#include <weft/collision/ImpactZones.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <string>

namespace weft::collision {
namespace {

const std::string kTwoCloths = std::string(WEFT_TEST_DATA_DIR) + "/scenes/two_cloths.json";
constexpr int kSteps = 45;  // the upper cloth lands on the lower one from about step 30

TEST(CollisionImpactZoneResponse, ObserverSeesEveryResponseAndItsZones) {
  const Scene scene = loadScene(kTwoCloths);
  Simulator sim(scene);
  ImpactZoneResponse* response = sim.impactZoneResponse();
  ASSERT_NE(response, nullptr);
  ASSERT_EQ(static_cast<int>(response->nodes().size()), response->nodeCount());
  int calls = 0, zonesSeen = 0, constraintsSeen = 0, zoneRecords = 0;
  NodeMatrix last;
  response->setObserver([&](const ImpactZoneResult& result) {
    ++calls;
    zonesSeen += result.stats.zones;
    constraintsSeen += result.stats.constraints;
    ASSERT_EQ(result.positions.rows(), response->nodeCount());
    last = result.positions;
    for (const ImpactZoneRecord& zone : result.zones) {
      ++zoneRecords;
      const ZoneQp qp = zone.sparse ? toDense(zone.sparseQp) : zone.qp;
      const Eigen::Index n = 3 * static_cast<Eigen::Index>(zone.nodes.size());
      EXPECT_EQ(qp.x.size(), n);
      EXPECT_EQ(qp.G.rows(), static_cast<Eigen::Index>(zone.impacts.size()));
      EXPECT_EQ(qp.G.cols(), n);
      EXPECT_EQ(zone.solution.z.size(), n);
      EXPECT_EQ(zone.solution.lambda.size(), qp.G.rows());
      // The response's positions are the zone's QP solution at its nodes.
      for (std::size_t i = 0; i < zone.nodes.size(); ++i)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(result.positions(zone.nodes[i], c),
                    zone.solution.z[3 * static_cast<Eigen::Index>(i) + c]);
    }
  });
  int zonesInStats = 0, constraintsInStats = 0, pieces = 0;
  for (int s = 0; s < kSteps; ++s) {
    const StepStats& st = sim.step();
    zonesInStats += st.impactZones;
    constraintsInStats += st.impactConstraints;
    pieces += std::max(1, st.substeps);
    // The last response of the step is where the step ends, on the collision mesh's nodes.
    for (int v = 0; v < response->nodeCount(); ++v)
      EXPECT_EQ(sim.positions().row(response->nodes()[static_cast<std::size_t>(v)]), last.row(v))
          << "step " << s + 1 << ", vertex " << v;
  }
  EXPECT_EQ(calls, pieces);  // one response per accepted solve
  EXPECT_EQ(zonesSeen, zonesInStats);
  EXPECT_EQ(zoneRecords, zonesInStats);
  EXPECT_EQ(constraintsSeen, constraintsInStats);
  EXPECT_GT(zonesSeen, 0) << "the cloths should have landed on each other by step " << kSteps;
}

TEST(CollisionImpactZoneResponse, ObservingChangesNothing) {
  const Scene scene = loadScene(kTwoCloths);
  Simulator plain(scene), observed(scene);
  int calls = 0;
  observed.impactZoneResponse()->setObserver([&](const ImpactZoneResult&) { ++calls; });
  for (int s = 0; s < kSteps; ++s) {
    plain.step();
    observed.step();
  }
  EXPECT_GT(calls, 0);
  EXPECT_TRUE(plain.positions() == observed.positions());
  EXPECT_TRUE(plain.velocities() == observed.velocities());
  // Removing the observer stops the calls.
  observed.impactZoneResponse()->setObserver(nullptr);
  const int before = calls;
  observed.step();
  EXPECT_EQ(calls, before);
}

TEST(CollisionImpactZoneResponse, NoResponseWithoutImpactZones) {
  const Scene scene = loadScene(std::string(WEFT_TEST_DATA_DIR) + "/scenes/hanging.json");
  Simulator sim(scene);
  EXPECT_EQ(sim.impactZoneResponse(), nullptr);
}

}  // namespace
}  // namespace weft::collision
