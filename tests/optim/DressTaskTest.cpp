// The Dress task (DiffCloth Sec. 6.3, Fig. 1, Appendix B.3, Eq. 34; assets/scenes/dress.json and
// assets/meshes/dress.obj, written by scripts/make-dress.py): a pleated skirt whose waist turns
// about the vertical axis; its density and bending stiffness (2 DoF) are to make the hem reach the
// height of a 100 degree cone. The scene is what the paper describes, the twirl turns the waist and
// flares the skirt, a dress in the design valley meets the target far better than the start, and
// the adjoint gradient agrees with finite differences.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/HemlineLoss.h>
#include <weft/diff/ParameterSet.h>
#include <weft/optim/SimulationObjective.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

constexpr int kRing = 32;  // vertices per ring (16 pleats)
constexpr int kRings = 9;

std::string dressFile() {
  return std::string(WEFT_ASSET_DIR) + "/scenes/dress.json";
}

// The dress over its first `steps` steps, the hemline term at `states`.
Scene shortened(int steps, const std::vector<int>& states) {
  const Scene full = loadScene(dressFile(), {});
  nlohmann::json doc = full.document;
  doc["time"]["steps"] = steps;
  doc["task"]["loss"]["hemline"]["steps"] = states;
  return parseScene(doc, full.file, full.directory);
}

// Mean distance of the hem ring from the vertical axis at state `s`.
double hemRadius(const Trajectory& t, int s) {
  double r = 0.0;
  for (int i = (kRings - 1) * kRing; i < kRings * kRing; ++i)
    r += std::hypot(t.positions[s](i, 0), t.positions[s](i, 2));
  return r / kRing;
}

TEST(DressTask, SceneIsThePapersTwirlDress) {
  const Scene scene = loadScene(dressFile(), {});
  EXPECT_DOUBLE_EQ(scene.time.dt, 1.0 / 120.0);  // Fig. 1 and Table 4: h = 1/120 s, 125 steps
  EXPECT_EQ(scene.time.steps, 125);
  ASSERT_EQ(scene.cloths.size(), 1u);
  EXPECT_EQ(scene.vertexCount(), kRings * kRing);
  // No obstacle, wind or self-contact: the paper's dress only spins.
  EXPECT_TRUE(scene.obstacles.empty());
  EXPECT_FALSE(scene.wind);
  EXPECT_FALSE(scene.hasSelfCollision());
  // The waist ring is one handle turning about +Y through the waist centre.
  const Cloth& dress = scene.cloths[0];
  ASSERT_EQ(dress.attachments.size(), 1u);
  const Attachment& waist = dress.attachments[0];
  EXPECT_EQ(waist.kind, Attachment::Kind::Handle);
  ASSERT_EQ(waist.vertices.size(), static_cast<std::size_t>(kRing));
  EXPECT_TRUE(waist.trajectory.rotates);
  EXPECT_LT((waist.trajectory.rotationAxis - Vec3::UnitY()).norm(), 1e-12);
  EXPECT_NE(waist.trajectory.rotationRateDeg, 0.0);
  for (int v : waist.vertices) {
    EXPECT_NEAR(dress.mesh.vertices(v, 1), waist.trajectory.rotationCenter.y(), 1e-12) << v;
    EXPECT_NEAR(std::hypot(dress.mesh.vertices(v, 0), dress.mesh.vertices(v, 2)), 0.12, 1e-9) << v;
  }
  // Eq. 34's hemline: the lowest ring, against the height of a 100 degree cone hung from the
  // waist with the skirt's slant length.
  ASSERT_TRUE(scene.task);
  const nlohmann::json& hemline = scene.task->loss.at("hemline");
  ASSERT_EQ(hemline.at("vertices").size(), static_cast<std::size_t>(kRing));
  const double lowest = dress.mesh.vertices.col(1).minCoeff();
  for (int v : hemline.at("vertices")) EXPECT_NEAR(dress.mesh.vertices(v, 1), lowest, 1e-12) << v;
  const TaskLoss loss(scene);
  ASSERT_EQ(loss.terms().size(), 1u);
  const auto* hem = dynamic_cast<const HemlineLoss*>(loss.terms()[0].get());
  ASSERT_NE(hem, nullptr);
  EXPECT_NEAR(hem->height(), 1.0 - 0.48 * std::cos(50.0 * M_PI / 180.0), 1e-12);
  // The paper's two parameters, bounded.
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  ASSERT_EQ(parameters.size(), 2);
  EXPECT_EQ(parameters[0].kind, SceneParameter::Kind::Density);
  EXPECT_EQ(parameters[1].kind, SceneParameter::Kind::Bend);
  const SimulationObjective objective(scene, parameters);
  for (const SceneParameter& p : objective.space().parameters())
    EXPECT_TRUE(p.lower > 0.0 && std::isfinite(p.upper)) << p.path;
}

TEST(DressTask, TwirlTurnsTheWaistAndFlaresTheSkirt) {
  // Half a second (60 steps): the waist has turned 180 degrees at 360 deg/s, keeping its radius,
  // and the hem has moved out from the axis, further than without the spin.
  const Scene scene = shortened(60, {60});
  const ForwardPass spun = runForwardPass(scene);
  EXPECT_EQ(spun.unconvergedSteps, 0);
  const Trajectory& t = spun.trajectory;
  const double turned = scene.cloths[0].attachments[0].trajectory.rotationRateDeg * 0.5;
  ASSERT_NEAR(std::abs(turned), 180.0, 1e-9);
  for (int v : {0, 7, 16}) {
    const Vec3 x0 = t.positions[0].row(v).transpose(), x = t.positions[60].row(v).transpose();
    // Vertex 0 starts on +X; the others are checked by their angle change.
    const double a0 = std::atan2(x0.z(), x0.x()), a = std::atan2(x.z(), x.x());
    double d = std::remainder((a - a0) * 180.0 / M_PI, 360.0);
    EXPECT_NEAR(std::abs(d), 180.0, 1.0) << v;
    EXPECT_NEAR(std::hypot(x.x(), x.z()), 0.12, 1e-3) << v;  // the handle springs hold the waist
  }
  const Scene still =
      withDocumentValue(scene, "cloths.0.attachments.0.trajectory.rotate.degrees_per_second", 0.0);
  const Trajectory hanging = runForwardPass(still).trajectory;
  EXPECT_GT(hemRadius(t, 60), hemRadius(hanging, 60) + 0.02);
}

TEST(DressTask, HeavierSofterDressMeetsTheApexAngle) {
  // The full task: the light, stiff starting dress barely opens (its hem ends about 9 cm below
  // the target); a heavier, softer one in the design valley (density 0.3 kg/m^2, bend 7.3e-4 N m,
  // L-BFGS-B's first step from the start) comes far closer to the 100 degree cone.
  const Scene scene = loadScene(dressFile(), {});
  SimulationObjective start(scene, ParameterSet::fromTask(scene));
  const ParameterSpace& space = start.space();
  const double initial = start.value(space.toCoordinates(space.initialValues()));
  Eigen::VectorXd designed(2);
  designed << 0.3, 7.3e-4;
  const double better = start.value(space.toCoordinates(designed));
  EXPECT_GT(initial, 0.1);  // m^2, summed over 31 states
  EXPECT_LT(better, 0.25 * initial);
}

TEST(DressTask, AdjointGradientMatchesFiniteDifferencesAtReducedSize) {
  // 30 steps (the hemline over states 20..30): density and bend, adjoint (direct backward solve)
  // against central finite differences to 1e-4 relative.
  std::vector<int> states;
  for (int s = 20; s <= 30; ++s) states.push_back(s);
  const Scene scene = shortened(30, states);
  test::expectAdjointMatchesFiniteDifferences(scene);
}

}  // namespace
}  // namespace weft
