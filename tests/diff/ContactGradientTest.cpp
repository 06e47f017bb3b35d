// Gradients through frictional contact (DiffCloth Sec. 4.2, ContactAdjoint.h) against central
// finite differences of the task loss: a ribbon sliding down an incline (slip branch), a small
// cloth resting on a sphere (stick branch, curved frames), the same cloth sliding over the sphere,
// and a cloth pushed into a wall (nodes touching two planes: coupled contacts). The scenes keep
// their contact set constant under the finite-difference probes: a contact appearing or vanishing
// between the +/- runs is a jump no derivative describes.
//
// Agreement test: |adjoint - fd| <= 1e-4 max(|adjoint|, |fd|) + 1e-6 max_k |adjoint_k|, i.e. a
// relative error below 1e-4 on every component that is not negligible against the gradient's
// largest (stretch and density barely move a sliding ribbon; their finite differences are then
// round-off and forward-tolerance noise, measured at 1e-13 of the friction derivative).

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/TaskLoss.h>
#include <weft/mesh/RigidTransform.h>
#include <weft/scene/JsonPath.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace weft {
namespace {

using test::TempDir;

nlohmann::json sphereScene(double friction, double speed) {
  // A soft, heavy 6 cm cloth laid on top of a 0.3 m sphere (h^2 k below the nodal mass, so the
  // forward's contact iteration converges tightly), pushed sideways.
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "sphere", "time": {"dt": 0.01, "steps": 15}, "gravity": [0, -9.8, 0],
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4},
    "cloths": [{"mesh": {"grid": {"size": [0.06, 0.06], "resolution": [3, 3]},
                         "transform": {"translate": [0, 0.3005, 0]}},
                "material": {"density": 1.0, "stretch": 20.0, "bend": 0.0005}}],
    "obstacles": [{"sphere": {"center": [0, 0, 0], "radius": 0.3}}]})");
  doc["obstacles"][0]["friction"] = friction;
  doc["cloths"][0]["initial_velocity"] = {speed, 0.0, speed / 3.0};
  return doc;
}

nlohmann::json cornerScene() {
  // A cloth on a floor sliding along a wall it is pushed into: the nodes of the edge at the wall
  // touch both planes, so their two contacts couple (ContactAdjoint's T).
  return nlohmann::json::parse(R"({
    "name": "corner", "time": {"dt": 0.01, "steps": 10}, "gravity": [0, -9.8, 0],
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4},
    "cloths": [{"mesh": {"grid": {"size": [0.06, 0.06], "resolution": [3, 3]}, "transform": {"translate": [0, 0.0005, 0]}},
                "material": {"density": 1.0, "stretch": 20.0, "bend": 0.0005}, "initial_velocity": [0.1, 0, 0.3]}],
    "obstacles": [{"plane": {"point": [0, 0, 0], "normal": [0, 1, 0]}, "friction": 0.3},
                  {"plane": {"point": [0.0305, 0, 0], "normal": [-1, 0, 0]}, "friction": 0.2}]})");
}

// The document with a trajectory task whose target is the document simulated with `changes`.
Scene withTask(const TempDir& dir, nlohmann::json doc,
               const std::vector<std::pair<std::string, double>>& changes,
               const std::vector<std::string>& parameters) {
  nlohmann::json target = doc;
  for (const auto& [path, value] : changes) *findJsonPath(target, path) = value;
  const std::string file = test::writeTargetTrajectory(target, dir.file("target.npy"));
  test::addTask(doc, "trajectory", file, parameters);
  return test::parse(doc);
}

struct BranchCounts {
  int stick = 0, slip = 0;
};

BranchCounts branchesOf(const Scene& scene) {
  const ForwardPass pass = runForwardPass(withTightForwardSolver(scene, 1e-8));
  BranchCounts counts;
  for (const StepStats& s : pass.trajectory.steps) counts.stick += s.stick, counts.slip += s.slip;
  return counts;
}

GradientCheckOptions options(const char* method = nullptr) {
  GradientCheckOptions o;
  o.eps = 1e-3;  // above the forward tolerance's noise, below any contact-set change
  if (method) o.backwardMethod = method;
  return o;
}

TEST(ContactGradient, RibbonSlidingDownAnInclineSlipBranch) {
  TempDir dir;
  const Scene scene = withTask(
      dir, test::inclineScene(),
      {{"obstacles.0.friction", 0.25}, {"cloths.0.material.stretch", 120.0}},
      {"obstacles.0.friction", "cloths.0.initial_velocity.0", "cloths.0.initial_velocity.2",
       "gravity.1", "cloths.0.material.density", "cloths.0.material.stretch"});
  const BranchCounts branches = branchesOf(scene);
  EXPECT_EQ(branches.stick, 0);
  EXPECT_GT(branches.slip, 30 * 15);  // nearly every node slips on every step
  const GradientCheckReport report = checkGradient(scene, ParameterSet::fromTask(scene), options());
  test::expectGradientAgreement(report);
  EXPECT_GT(std::abs(report.entries[0].adjoint), 0.1);  // friction decides the motion
}

TEST(ContactGradient, EveryBackwardSolverGivesTheSameContactGradientAndTheFixedPointFallsBack) {
  // Slip rows pin the normal motion (dr/df = -n n^T): rho(P^-1 (Delta P + Delta R)) is about
  // 1 - m / (h^2 k) there, and DiffCloth's fixed point stalls; the direct fallback must recover
  // the same gradient (issue: "a case built to make the fixed-point iteration diverge").
  TempDir dir;
  const Scene scene = withTask(dir, test::inclineScene(), {{"obstacles.0.friction", 0.25}},
                               {"obstacles.0.friction", "cloths.0.initial_velocity.0"});
  const Scene tight = withTightForwardSolver(scene, 1e-8);
  const ForwardPass pass = runForwardPass(tight);
  const TaskLoss loss(tight);
  BackwardSettings settings = tight.solver.backward;
  settings.tolerance = 1e-10;
  settings.maxIterations = 400;
  std::vector<Eigen::VectorXd> gradients;
  for (const char* method : {"direct", "gmres", "fixed_point"}) {
    SCOPED_TRACE(method);
    settings.method = method;
    const GradientResult g =
        backpropagate(pass.trajectory, loss, ParameterSet::fromTask(tight), settings);
    gradients.push_back(g.gradient);
    if (std::string(method) == "gmres") {
      EXPECT_EQ(g.solver.fallbacks, 0);
    } else if (std::string(method) == "fixed_point") {
      EXPECT_GT(g.solver.fallbacks, 0);
    }
  }
  for (std::size_t k = 1; k < gradients.size(); ++k)
    EXPECT_LT((gradients[k] - gradients[0]).norm(), 1e-7 * gradients[0].norm())
        << gradients[k].transpose();
}

// On the sliding ribbon P needs a few iterations per step at the default tolerance, and a guess
// combined from previous solutions (solver.backward.history) can meet it at once: the gradient
// at the default tolerance must stay at least as close to the direct one as when each step
// starts from the last solution (here 1.2e-5 against 1.1e-3).
TEST(ContactGradient, PreviousSolutionsKeepTheGradientAtTheDefaultTolerance) {
  TempDir dir;
  const Scene scene = withTightForwardSolver(
      withTask(
          dir, test::inclineScene(), {{"obstacles.0.friction", 0.25}},
          {"obstacles.0.friction", "cloths.0.initial_velocity.0", "cloths.0.material.stretch"}),
      1e-8);
  BackwardSettings settings = scene.solver.backward;
  settings.tolerance = 1e-4;
  const test::HistoryGradients g = test::gradientsWithAndWithoutHistory(scene, settings);
  const GradientResult &direct = g.direct, &combined = g.combined, &lastOnly = g.lastOnly;
  const double errorLastOnly =
      (lastOnly.gradient - direct.gradient).norm() / direct.gradient.norm();
  const double errorCombined =
      (combined.gradient - direct.gradient).norm() / direct.gradient.norm();
  std::printf(
      "at 1e-4: gradient error %.3g from the last solution (%lld iterations), %.3g from the "
      "combination (%lld)\n",
      errorLastOnly, lastOnly.solver.iterations, errorCombined, combined.solver.iterations);
  EXPECT_LT(errorCombined, 2.0 * errorLastOnly + 1e-7);
}

TEST(ContactGradient, ClothRestingOnASphereStickBranchWithCurvedFrames) {
  TempDir dir;
  const Scene scene = withTask(
      dir, sphereScene(0.9, 0.05), {{"cloths.0.material.stretch", 24.0}, {"gravity.0", 0.5}},
      {"cloths.0.material.stretch", "cloths.0.material.density", "cloths.0.initial_velocity.0",
       "gravity.0", "gravity.1", "obstacles.0.friction"});
  const BranchCounts branches = branchesOf(scene);
  EXPECT_GT(branches.stick, 3 * 15);
  // A stuck cloth barely responds (gradient ~1e-7 of a loss ~1e-8): the finite differences carry
  // the forward tolerance's noise at about 1e-4 relative. With the forward converged to 1e-11 the
  // same comparison agrees to 1e-7 on most components (`weft gradcheck` with
  // --forward-tolerance 1e-11, 40 s: too slow for the suite), so the bound here is 1e-3, and the
  // friction derivative (zero: nothing slips) is compared to 1e-5 of the largest component.
  test::expectGradientAgreement(checkGradient(scene, ParameterSet::fromTask(scene), options()),
                                1e-3, 1e-5);
}

TEST(ContactGradient, ClothSlidingOverASphere) {
  TempDir dir;
  const Scene scene =
      withTask(dir, sphereScene(0.1, 0.3), {{"obstacles.0.friction", 0.12}, {"gravity.0", 0.5}},
               {"obstacles.0.friction", "cloths.0.material.density", "cloths.0.initial_velocity.0",
                "gravity.0", "cloths.0.material.stretch"});
  const BranchCounts branches = branchesOf(scene);
  EXPECT_EQ(branches.stick, 0);
  EXPECT_GT(branches.slip, 3 * 15);
  test::expectGradientAgreement(checkGradient(scene, ParameterSet::fromTask(scene), options()));
}

TEST(ContactGradient, NodesTouchingTwoObstaclesCoupleTheirContacts) {
  TempDir dir;
  const Scene scene =
      withTask(dir, cornerScene(), {{"obstacles.1.friction", 0.25}},
               {"obstacles.0.friction", "obstacles.1.friction", "cloths.0.initial_velocity.0",
                "cloths.0.initial_velocity.2", "cloths.0.material.density", "gravity.1"});
  const ForwardPass pass = runForwardPass(withTightForwardSolver(scene, 1e-8));
  int doubled = 0;  // steps with a node in contact with both planes
  for (const StepContacts& step : pass.trajectory.contacts) {
    std::vector<int> walls;
    for (const ContactPoint& p : step.points)
      if (p.obstacle == 1 && p.branch != ContactBranch::TakeOff) walls.push_back(p.node);
    for (const ContactPoint& p : step.points)
      if (p.obstacle == 0 && p.branch != ContactBranch::TakeOff &&
          std::find(walls.begin(), walls.end(), p.node) != walls.end()) {
        ++doubled;
        break;
      }
  }
  EXPECT_GE(doubled, 3);
  for (const char* method : {"gmres", "direct"}) {
    SCOPED_TRACE(method);
    test::expectGradientAgreement(
        checkGradient(scene, ParameterSet::fromTask(scene), options(method)));
  }
}

// The semismooth Newton contact solve (solver.contact = "newton") reaches the same forward
// solution, so the same adjoint holds; and it converges the stuck cloth to 1e-11 in well under a
// second (the PD iteration: 40 s), which takes the finite differences below the noise that limits
// the test above to 1e-3. The step is 1e-4: at 1e-3 the central difference's truncation error
// on the density component is 1.2e-4.
TEST(ContactGradient, NewtonForwardStickBranchAgreesToTheTightTolerance) {
  TempDir dir;
  nlohmann::json doc = sphereScene(0.9, 0.05);
  doc["solver"]["contact"] = "newton";
  const Scene scene = withTask(dir, doc, {{"cloths.0.material.stretch", 24.0}, {"gravity.0", 0.5}},
                               {"cloths.0.material.stretch", "cloths.0.material.density",
                                "cloths.0.initial_velocity.0", "gravity.0", "gravity.1"});
  EXPECT_GT(branchesOf(scene).stick, 3 * 15);
  GradientCheckOptions o = options();
  o.forwardTolerance = 1e-11;
  o.eps = 1e-4;
  test::expectGradientAgreement(checkGradient(scene, ParameterSet::fromTask(scene), o), 1e-4, 1e-6);
}

TEST(ContactGradient, NewtonForwardSlipAndCoupledContacts) {
  for (bool corner : {false, true}) {
    SCOPED_TRACE(corner ? "corner" : "incline");
    TempDir dir;
    nlohmann::json doc = corner ? cornerScene() : test::inclineScene();
    doc["solver"]["contact"] = "newton";
    const Scene scene =
        corner ? withTask(dir, doc, {{"obstacles.1.friction", 0.25}},
                          {"obstacles.0.friction", "obstacles.1.friction",
                           "cloths.0.initial_velocity.0", "cloths.0.material.density"})
               : withTask(dir, doc,
                          {{"obstacles.0.friction", 0.25}, {"cloths.0.material.stretch", 120.0}},
                          {"obstacles.0.friction", "cloths.0.initial_velocity.0",
                           "cloths.0.material.density", "cloths.0.material.stretch"});
    test::expectGradientAgreement(checkGradient(scene, ParameterSet::fromTask(scene), options()));
  }
}

// The corner with high friction on both planes and gravity pressing the cloth into the wall, so
// that the edge's nodes stick (or slip) on both at once; Newton's contact solve.
nlohmann::json pressedCornerScene() {
  nlohmann::json doc = cornerScene();
  doc["obstacles"][0]["friction"] = 2.0;
  doc["obstacles"][1]["friction"] = 2.0;
  doc["gravity"] = {2.0, -9.8, 0.0};
  doc["cloths"][0]["initial_velocity"] = {0.05, 0.0, 0.0};
  doc["solver"]["contact"] = "newton";
  // Whole steps: these tests are about the coupled contacts' adjoint on the contact states the
  // scene's steps produce; split steps record their last piece's (see the note of issue 36).
  doc["solver"]["max_halvings"] = 0;
  return doc;
}

// Nodes sticking to the floor and the wall at once have no unique impulse split (T^T = [I I; I I]
// for the two contacts of such a node: singular). The backward pass takes the minimum-norm split
// (ContactAdjoint::kSingularCouplingShift); the node's motion depends on the total only, so the
// gradient still matches finite differences. Before, the backward pass failed with exit 3 (seen
// on the Sock task, step 399 of its first L-BFGS-B evaluation).
TEST(ContactGradient, NodesStickingToTwoObstaclesAtOnce) {
  TempDir dir;
  nlohmann::json doc = pressedCornerScene();
  const Scene scene =
      withTask(dir, doc, {{"gravity.0", 2.5}},
               {"gravity.0", "cloths.0.material.density", "cloths.0.initial_velocity.0"});
  const ForwardPass pass = runForwardPass(withTightForwardSolver(scene, 1e-8));
  int doubleSticks = 0;  // (step, node) with a stick on both planes
  for (const StepContacts& step : pass.trajectory.contacts) {
    std::vector<int> floor, wall;
    for (const ContactPoint& p : step.points)
      if (p.branch == ContactBranch::Stick) (p.obstacle == 0 ? floor : wall).push_back(p.node);
    for (int node : floor) doubleSticks += std::count(wall.begin(), wall.end(), node) > 0;
  }
  EXPECT_GE(doubleSticks, 10);
  for (const char* method : {"gmres", "direct"}) {
    SCOPED_TRACE(method);
    test::expectGradientAgreement(
        checkGradient(scene, ParameterSet::fromTask(scene), options(method)));
  }
}

// The corner scene turned by `rotation` as a whole: cloth, planes, gravity and initial velocity.
nlohmann::json rotated(nlohmann::json doc, const RigidTransform& rotation) {
  const auto turn = [&](nlohmann::json& v) {
    const Vec3 r =
        rotation.rotation() * Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    v = {r.x(), r.y(), r.z()};
  };
  nlohmann::json& transform = doc["cloths"][0]["mesh"]["transform"];
  turn(transform["translate"]);
  transform["rotate_deg"] = {rotation.rotateDeg.x(), rotation.rotateDeg.y(),
                             rotation.rotateDeg.z()};
  for (nlohmann::json& o : doc["obstacles"]) turn(o["plane"]["point"]), turn(o["plane"]["normal"]);
  turn(doc["gravity"]);
  turn(doc["cloths"][0]["initial_velocity"]);
  return doc;
}

// A node sticking to one plane while it slips on the other: T^T = [I I; S I] for its two
// contacts, with S sharing I's normal direction, so the pair has no unique impulse split either.
// With the corner turned off the axes, rounding leaves the pair's zero singular values at about
// 1e-17 instead of exact zeros, and a sparse LU of T^T finds no zero pivot: before singular
// groups were found by their singular values, the direct solve of the augmented system failed
// (the Sock's first L-BFGS-B evaluation at bench seed 1, step 282, on its two capsules).
TEST(ContactGradient, NodesStickingToOneObstacleAndSlippingOnAnother) {
  TempDir dir;
  nlohmann::json doc = pressedCornerScene();
  RigidTransform turn;
  turn.rotateDeg = Vec3(17.0, 29.0, 11.0);
  doc = rotated(doc, turn);
  const Vec3 gravity = turn.rotation() * Vec3(2.5, -9.8, 0.0);
  const Scene scene =
      withTask(dir, doc,
               {{"gravity.0", gravity.x()}, {"gravity.1", gravity.y()}, {"gravity.2", gravity.z()}},
               {"gravity.0", "cloths.0.material.density", "cloths.0.initial_velocity.0"});
  const ForwardPass pass = runForwardPass(withTightForwardSolver(scene, 1e-8));
  int stickSlips = 0;  // (step, node) with a stick on one plane and a slip on the other
  for (const StepContacts& step : pass.trajectory.contacts)
    for (const ContactPoint& p : step.points)
      for (const ContactPoint& q : step.points)
        stickSlips += p.node == q.node && p.obstacle == 0 && q.obstacle == 1 &&
                      ((p.branch == ContactBranch::Stick && q.branch == ContactBranch::Slip) ||
                       (p.branch == ContactBranch::Slip && q.branch == ContactBranch::Stick));
  EXPECT_GE(stickSlips, 10);
  for (const char* method : {"gmres", "direct"}) {
    SCOPED_TRACE(method);
    test::expectGradientAgreement(
        checkGradient(scene, ParameterSet::fromTask(scene), options(method)));
  }
}

}  // namespace
}  // namespace weft

namespace weft {
namespace {

// Adaptive time stepping (SolverSettings::maxHalvings): the backward pass runs through a split
// step's pieces, each with its own dt, P and contacts. A cloth sliding over a sphere with a
// budget of 14 Newton solves per step at 1e-9 m/s^2 splits every step into 2-4 pieces; the
// gradient is compared with central differences of runs split the same way.
TEST(ContactGradient, GradientsFollowTheStepsAdaptiveTimeSteppingSplit) {
  TempDir dir;
  nlohmann::json doc = sphereScene(0.1, 0.3);
  doc["solver"] = {{"method", "newton"},
                   {"contact", "newton"},
                   {"pd_iterations", 14},
                   {"pd_tolerance", 1e-9},
                   {"max_halvings", 4}};
  doc["gravity"][0] = 0.5;
  const Scene scene =
      withTask(dir, doc, {{"obstacles.0.friction", 0.12}},
               {"obstacles.0.friction", "cloths.0.material.density", "cloths.0.initial_velocity.0",
                "gravity.0", "cloths.0.material.stretch"});
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  const TaskLoss loss(scene);
  auto pattern = [](const Trajectory& t) {
    std::vector<int> pieces;
    for (const auto& p : t.substeps) pieces.push_back(static_cast<int>(p.size()));
    return pieces;
  };
  const ForwardPass base = runForwardPass(scene);
  EXPECT_EQ(base.unconvergedSteps, 0);
  int split = 0;
  for (const auto& p : base.trajectory.substeps) split += p.size() > 1;
  EXPECT_GE(split, 10);
  BackwardSettings backward = scene.solver.backward;
  backward.tolerance = 1e-10;
  const GradientResult adjoint = backpropagate(base.trajectory, loss, parameters, backward);

  GradientCheckReport report;
  const Eigen::VectorXd values = parameters.values(scene);
  for (int k = 0; k < parameters.size(); ++k) {
    GradientCheckEntry e;
    e.param = parameters[k].path;
    e.step = 1e-4 * std::abs(values[k]);
    double side[2];
    for (int s = 0; s < 2; ++s) {
      Eigen::VectorXd shifted = values;
      shifted[k] += s == 0 ? e.step : -e.step;
      const ForwardPass run = runForwardPass(parameters.compile(scene, shifted));
      report.unconvergedSteps += run.unconvergedSteps;
      ASSERT_EQ(pattern(run.trajectory), pattern(base.trajectory)) << e.param;
      side[s] = loss.value(run.trajectory.model->scene(), run.trajectory);
    }
    e.finiteDifference = (side[0] - side[1]) / (2.0 * e.step);
    e.adjoint = adjoint.gradient[k];
    report.entries.push_back(e);
  }
  test::expectGradientAgreement(report);
}

}  // namespace
}  // namespace weft
