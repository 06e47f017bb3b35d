// Gradients through self-collision pairs (DiffCloth Sec. 4.3: node-node contacts whose frame is
// the pair's relative position, n = (x_a - x_b)/|x_a - x_b|, so J_n = J_n(x_n) with two nonzero
// blocks per row) against central finite differences of the task loss.
//
// The scene: two separate square cloths stacked node over node, the lower one lying on a floor,
// the upper one resting on it at the collision distance. Gravity is tilted (an incline without
// the incline): its tangential part exceeds the pairs' Coulomb bound and stays below the floor's,
// so the lower cloth sticks to the floor while the upper one slips over it (Eq. 8's slip branch,
// whose dL/dmu is what cloths.K.self_collision.friction differentiates). Every lower node carries
// a floor contact and a pair: the two contacts share the node and couple (ContactAdjoint's T).
// A small force on one corner of the upper cloth makes it deform as it slides.
//
// Before SelfCollisionDetector excluded only mesh neighbours, this scene had no pairs at all: the
// cloths start 20 mm apart, inside the 30 mm reach, and every pair closer than the reach in the
// rest mesh was excluded, cloth or no cloth.
//
// Why the run is short and the grid coarse: a node sliding over a node sees the pair's normal
// tilt by about (offset / collision distance), which pushes it further out like a ball on top of
// a ball (growth rate sqrt(g / d)). With d = 2 cm and 10 steps of 0.01 s the upper cloth moves
// a few millimetres, far less than the ~2 cm after which a pair would break, and the 4 cm grid
// spacing keeps every node's partner unique (no diagonal pairs within the 3 cm reach). The test
// asserts that the pair set and every pair's branch are the same on every step and under the
// finite-difference probes of the friction: a pair appearing or vanishing is a jump that no
// derivative describes.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/TaskLoss.h>
#include <weft/scene/JsonPath.h>

#include <gtest/gtest.h>

#include <set>
#include <tuple>

namespace weft {
namespace {

using test::TempDir;

constexpr int kQuads = 3;          // per side, per cloth: 16 nodes
constexpr double kSpacing = 0.04;  // m between grid nodes
constexpr double kRadius = 0.02;   // collision distance d (m)
constexpr int kSteps = 10;

nlohmann::json stackedClothsScene() {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "stacked", "time": {"dt": 0.01}, "gravity": [1.8, -9.8, 0],
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4},
    "obstacles": [{"plane": {"point": [0, 0, 0], "normal": [0, 1, 0]}, "friction": 0.6}]})");
  doc["time"]["steps"] = kSteps;
  const double size = kQuads * kSpacing;
  for (int k = 0; k < 2; ++k) {
    // The lower cloth 0.5 mm above the floor, the upper exactly the collision distance above it.
    const double height = 0.0005 + k * kRadius;
    nlohmann::json cloth = {{"mesh",
                             {{"grid", {{"size", {size, size}}, {"resolution", {kQuads, kQuads}}}},
                              {"transform", {{"translate", {0.0, height, 0.0}}}}}},
                            {"material", {{"density", 1.0}, {"stretch", 20.0}, {"bend", 0.0005}}},
                            {"self_collision", {{"radius", kRadius}, {"friction", 0.15}}}};
    if (k == 1) {
      cloth["initial_velocity"] = {0.005, 0.0, 0.002};
      // A small pull on one corner (the last node) makes the upper cloth deform as it slides, so
      // its density matters (under gravity and Coulomb friction alone a uniform slide does not
      // depend on the mass).
      cloth["forces"] = nlohmann::json::array(
          {{{"vertices", {(kQuads + 1) * (kQuads + 1) - 1}}, {"force", {0.0003, 0.0, 0.0}}}});
    }
    doc["cloths"].push_back(cloth);
  }
  return doc;
}

// Every pair of a run with its branch, per step.
using PairRecord = std::set<std::tuple<int, int, int>>;  // (node, partner, branch)

struct PairRun {
  std::vector<PairRecord> steps;
  double largestSlide = 0.0;  // largest tangential offset of a pair's nodes (m)
  int unconverged = 0;
};

PairRun pairsOf(const nlohmann::json& doc) {
  const ForwardPass pass = runForwardPass(withTightForwardSolver(test::parse(doc), 1e-8));
  PairRun run;
  run.unconverged = pass.unconvergedSteps;
  for (std::size_t n = 0; n < pass.trajectory.contacts.size(); ++n) {
    PairRecord record;
    for (const ContactPoint& p : pass.trajectory.contacts[n].points) {
      if (p.partner < 0) continue;
      record.emplace(p.node, p.partner, static_cast<int>(p.branch));
      const Vec3 d = pass.trajectory.positions[n + 1].row(p.node) -
                     pass.trajectory.positions[n + 1].row(p.partner);
      run.largestSlide = std::max(run.largestSlide, std::hypot(d.x(), d.z()));
    }
    run.steps.push_back(record);
  }
  return run;
}

// The document with a trajectory task whose target is the document simulated with `changes`.
Scene withTask(const TempDir& dir, nlohmann::json doc,
               const std::vector<std::pair<std::string, double>>& changes,
               const std::vector<std::string>& parameters) {
  nlohmann::json target = doc;
  for (const auto& [path, value] : changes) *findJsonPath(target, path) = value;
  test::addTask(doc, "trajectory", test::writeTargetTrajectory(target, dir.file("target.npy")),
                parameters);
  return test::parse(doc);
}

TEST(SelfCollisionGradient, ClothSlippingOverAnotherClothMatchesFiniteDifferences) {
  const nlohmann::json doc = stackedClothsScene();
  const int nodes = (kQuads + 1) * (kQuads + 1);

  // The pairs exist on every step: each upper node over the lower node under it, all slipping,
  // the same set throughout.
  const PairRun run = pairsOf(doc);
  ASSERT_EQ(run.steps.size(), static_cast<std::size_t>(kSteps));
  PairRecord expected;
  for (int i = 0; i < nodes; ++i)
    expected.emplace(i, nodes + i, static_cast<int>(ContactBranch::Slip));
  for (int n = 0; n < kSteps; ++n) EXPECT_EQ(run.steps[n], expected) << "step " << n + 1;
  EXPECT_EQ(run.unconverged, 0);
  RecordProperty("largest_slide_m", std::to_string(run.largestSlide));
  EXPECT_GT(run.largestSlide, 1e-4);            // the upper cloth does slide
  EXPECT_LT(run.largestSlide, 0.25 * kRadius);  // far from breaking a pair

  // The probes change nothing discrete: the same pairs in the same branches at friction
  // 0.15 (1 +/- 1e-3), ten times the gradient check's step.
  for (double scale : {1.0 - 1e-3, 1.0 + 1e-3}) {
    nlohmann::json probe = doc;
    probe["cloths"][1]["self_collision"]["friction"] = 0.15 * scale;
    EXPECT_EQ(pairsOf(probe).steps, run.steps) << "friction scaled by " << scale;
  }

  // Target: the same scene with a rougher upper cloth and a faster push. The pair's friction
  // is the mean of its cloths' (SelfCollisionDetector), so cloths.1's coefficient acts through it.
  TempDir dir;
  const Scene scene =
      withTask(dir, doc,
               {{"cloths.1.self_collision.friction", 0.17}, {"cloths.1.initial_velocity.0", 0.008}},
               {"cloths.1.self_collision.friction", "cloths.0.self_collision.friction",
                "cloths.1.initial_velocity.0", "cloths.1.initial_velocity.2",
                "cloths.1.material.density", "gravity.0"});
  test::expectAdjointMatchesFiniteDifferences(scene);

  // The iterative path (GMRES on (P - Delta P - Delta R)^T z = g, Eq. 29, with Delta R applied
  // matrix-free through the coupled T) gives the direct augmented solve's gradient.
  const Scene tight = withTightForwardSolver(scene, 1e-8);
  const ForwardPass pass = runForwardPass(tight);
  const TaskLoss loss(tight);
  BackwardSettings settings = tight.solver.backward;
  settings.tolerance = 1e-10;
  settings.fallback = "none";
  Eigen::VectorXd gradients[2];
  for (int k = 0; k < 2; ++k) {
    settings.method = k == 0 ? "direct" : "gmres";
    gradients[k] =
        backpropagate(pass.trajectory, loss, ParameterSet::fromTask(tight), settings).gradient;
  }
  EXPECT_LT((gradients[1] - gradients[0]).norm(), 1e-7 * gradients[0].norm())
      << "direct " << gradients[0].transpose() << "\ngmres  " << gradients[1].transpose();
}

}  // namespace
}  // namespace weft
