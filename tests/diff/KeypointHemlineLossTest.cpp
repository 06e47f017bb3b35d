// The keypoint and hemline loss terms (DiffCloth Appendix B, Sock Eq. 33 and Dress Eq. 34):
// values as documented, state gradients against central differences of the term alone, the
// weighted sum of terms, the adjoint gradient of each w.r.t. stretch, bend and density against
// finite differences of the run, and bad input named by its JSON path.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/HemlineLoss.h>
#include <weft/diff/KeypointLoss.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/Npy.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace weft {
namespace {

using test::TempDir;

Trajectory randomTrajectory(int states, int nodes, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> n(0.0, 0.3);
  Trajectory t;
  for (int s = 0; s < states; ++s) {
    NodeMatrix x(nodes, 3);
    for (int i = 0; i < nodes; ++i)
      for (int c = 0; c < 3; ++c) x(i, c) = n(gen);
    t.positions.push_back(x);
  }
  return t;
}

// Every entry of the term's state gradient against a central difference of its value (the terms
// are quadratic in x, so the difference is exact up to round-off).
void expectGradientMatchesCentralDifferences(const LossTerm& term, Trajectory t) {
  std::vector<NodeMatrix> g(t.positions.size(), NodeMatrix::Zero(t.nodeCount(), 3));
  term.addGradient(t, g);
  const double step = 1e-4;
  for (std::size_t n = 0; n < t.positions.size(); ++n)
    for (int i = 0; i < t.nodeCount(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double x = t.positions[n](i, c);
        t.positions[n](i, c) = x + step;
        const double plus = term.value(t);
        t.positions[n](i, c) = x - step;
        const double minus = term.value(t);
        t.positions[n](i, c) = x;
        EXPECT_NEAR(g[n](i, c), (plus - minus) / (2 * step), 1e-9)
            << term.name() << " state " << n << " node " << i << " component " << c;
      }
}

TEST(KeypointLoss, SumsWeightedSquaredDistancesAtTheirSteps) {
  Trajectory t;
  t.positions = {NodeMatrix::Zero(3, 3), NodeMatrix::Zero(3, 3), NodeMatrix::Zero(3, 3)};
  t.positions[1](2, 0) = 1.0;
  t.positions[2](0, 1) = 2.0;
  // (state 1, vertex 2) is 1 m from the origin target; (state 2, vertex 0) 2 m off a target at
  // y = 4 ... and (state 2, vertex 1) sits on its target.
  const KeypointLoss loss(
      {{1, 2, Vec3::Zero(), 1.0}, {2, 0, Vec3(0, 4, 0), 0.5}, {2, 1, Vec3::Zero(), 7.0}}, 3.0);
  EXPECT_DOUBLE_EQ(loss.value(t), 3.0 * (1.0 + 0.5 * 4.0));
  std::vector<NodeMatrix> g(3, NodeMatrix::Zero(3, 3));
  loss.addGradient(t, g);
  EXPECT_TRUE(g[0].isZero());
  EXPECT_DOUBLE_EQ(g[1](2, 0), 3.0 * 2.0 * 1.0);
  EXPECT_DOUBLE_EQ(g[2](0, 1), 3.0 * 0.5 * 2.0 * -2.0);
  EXPECT_DOUBLE_EQ(g[2].row(1).norm(), 0.0);
}

TEST(KeypointLoss, GradientMatchesCentralDifferences) {
  const KeypointLoss loss({{0, 1, Vec3(0.1, -0.2, 0.3), 1.0},
                           {2, 1, Vec3(0.5, 0.5, 0.0), 2.5},
                           {2, 3, Vec3(-0.1, 0.0, 0.2), 0.3},
                           {2, 3, Vec3(0.4, 0.1, 0.0), 1.0}},  // a vertex may appear twice
                          1.7);
  expectGradientMatchesCentralDifferences(loss, randomTrajectory(3, 4, 7));
}

TEST(HemlineLoss, IsTheMeanSquaredHeightGapSummedOverSteps) {
  Trajectory t;
  t.positions = {NodeMatrix::Zero(3, 3), NodeMatrix::Zero(3, 3)};
  t.positions[1].col(1) << 1.0, 2.0, 5.0;  // heights of the three nodes at state 1
  const HemlineLoss loss({0, 1}, {1}, Vec3::UnitY(), 1.5, 2.0);
  EXPECT_DOUBLE_EQ(loss.value(t), 2.0 * (0.25 + 0.25) / 2.0);
  std::vector<NodeMatrix> g(2, NodeMatrix::Zero(3, 3));
  loss.addGradient(t, g);
  EXPECT_TRUE(g[0].isZero());
  EXPECT_DOUBLE_EQ(g[1](0, 1), 2.0 * 2.0 * -0.5 / 2.0);
  EXPECT_DOUBLE_EQ(g[1](1, 1), 2.0 * 2.0 * 0.5 / 2.0);
  EXPECT_DOUBLE_EQ(g[1](2, 1), 0.0);
  EXPECT_DOUBLE_EQ(g[1](0, 0), 0.0);
}

TEST(HemlineLoss, GradientMatchesCentralDifferencesAlongAnyUpVector) {
  const HemlineLoss loss({0, 2, 3}, {1, 3}, Vec3(0.3, 0.9, -0.2).normalized(), 0.25, 1.3);
  expectGradientMatchesCentralDifferences(loss, randomTrajectory(4, 5, 11));
}

TEST(HemlineLoss, TargetHeightFromTheApexAngle) {
  // A cone opened to 90 degrees puts a hem 1 m down its side at 1/sqrt(2) m below the apex; flat
  // out (180 degrees) at the apex height, closed (0 degrees) a full slant length below it.
  EXPECT_NEAR(targetHemlineHeight(90.0, 2.0, 1.0), 2.0 - std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(targetHemlineHeight(180.0, 2.0, 1.0), 2.0, 1e-15);
  EXPECT_NEAR(targetHemlineHeight(0.0, 2.0, 1.0), 1.0, 1e-15);
}

// The hanging wind cloth (7 x 7 vertices, bottom row 42..48 at about 0.8 m) with the new terms.
nlohmann::json keypointTerm() {
  return {
      {"points",
       {{{"step", 8},
         {"vertices", {48, 45}},
         {"positions", {{0.22, 0.79, 0.04}, {0.0, 0.78, 0.03}}}},
        {{"step", 20}, {"vertices", {42}}, {"positions", {{-0.18, 0.82, 0.06}}}, {"weight", 2.0}}}},
      {"weight", 5.0}};
}

nlohmann::json hemlineTerm() {
  return {{"vertices", {42, 43, 44, 45, 46, 47, 48}}, {"height", 0.83}, {"steps", {12, 20}}};
}

TEST(TaskLoss, SumsItsWeightedTerms) {
  TempDir dir;
  nlohmann::json doc = test::windClothScene(6, 20);
  const std::string target = test::writeTargetTrajectory(doc, dir.file("run.npy"));
  test::addTask(doc, "final", target, {});
  doc["task"]["loss"]["final"]["weight"] = 0.5;
  doc["task"]["loss"]["keypoints"] = keypointTerm();
  doc["task"]["loss"]["hemline"] = hemlineTerm();
  doc["task"]["loss"]["hemline"]["weight"] = 4.0;
  const Scene scene = test::parse(doc);
  const TaskLoss loss(scene);
  ASSERT_EQ(loss.terms().size(), 3u);
  // A trajectory that is the target run shifted by 1 cm in x at every state.
  Trajectory t;
  NpyArray npy = readNpy(target);
  for (std::size_t s = 0; s < npy.shape[0]; ++s) {
    NodeMatrix x(49, 3);
    for (int i = 0; i < 49; ++i)
      for (int c = 0; c < 3; ++c) x(i, c) = npy.data[(s * 49 + i) * 3 + c] + (c == 0 ? 0.01 : 0.0);
    t.positions.push_back(x);
  }
  double expected = 0.5 * 49 * 1e-4;  // the final-frame term
  const NodeMatrix& x8 = t.positions[8];
  const NodeMatrix& x20 = t.positions[20];
  expected += 5.0 * ((x8.row(48) - Eigen::RowVector3d(0.22, 0.79, 0.04)).squaredNorm() +
                     (x8.row(45) - Eigen::RowVector3d(0.0, 0.78, 0.03)).squaredNorm() +
                     2.0 * (x20.row(42) - Eigen::RowVector3d(-0.18, 0.82, 0.06)).squaredNorm());
  double hem = 0.0;
  for (int n : {12, 20})
    for (int i = 42; i <= 48; ++i) hem += std::pow(t.positions[n](i, 1) - 0.83, 2);
  expected += 4.0 * hem / 7.0;
  EXPECT_NEAR(loss.value(scene, t), expected, 1e-12 * expected);
}

const std::vector<std::string> kMaterial = {"cloths.0.material.stretch", "cloths.0.material.bend",
                                            "cloths.0.material.density"};

TEST(KeypointLoss, AdjointMatchesFiniteDifferencesForTheMaterial) {
  nlohmann::json doc = test::windClothScene(6, 20);
  doc["task"] = {{"loss", {{"keypoints", keypointTerm()}}}, {"parameters", kMaterial}};
  test::expectAdjointMatchesFiniteDifferences(test::parse(doc));
}

TEST(HemlineLoss, AdjointMatchesFiniteDifferencesForTheMaterial) {
  nlohmann::json doc = test::windClothScene(6, 20);
  doc["task"] = {{"loss", {{"hemline", hemlineTerm()}}}, {"parameters", kMaterial}};
  test::expectAdjointMatchesFiniteDifferences(test::parse(doc));
}

TEST(KeypointLoss, TargetFromARecordedRunIsReadAtTheEntrysStep) {
  TempDir dir;
  nlohmann::json doc = test::windClothScene(4, 6);  // 25 vertices
  const std::string run = test::writeTargetTrajectory(doc, dir.file("run.npy"));
  doc["task"] = {
      {"loss",
       {{"keypoints", {{"points", {{{"step", 4}, {"vertices", {24, 20}}, {"target", run}}}}}}}}};
  const Scene scene = test::parse(doc);
  const TaskLoss loss(scene);
  const auto& keypoints = dynamic_cast<const KeypointLoss&>(*loss.terms().front()).keypoints();
  ASSERT_EQ(keypoints.size(), 2u);
  const NpyArray npy = readNpy(run);
  for (int k = 0; k < 2; ++k) {
    const int v = k == 0 ? 24 : 20;
    EXPECT_EQ(keypoints[k].state, 4);
    EXPECT_EQ(keypoints[k].vertex, v);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(keypoints[k].target[c], npy.data[(4 * 25 + v) * 3 + c]);
  }
}

struct BadLoss {
  const char* name;
  nlohmann::json loss;
  std::string path, phrase;
};

// Bad keys are the loader's errors (any verb); bad target files are found when the loss is built.
TEST(TaskLoss, BadKeypointAndHemlineInputNamesItsJsonPath) {
  TempDir dir;
  const std::vector<double> zeros(7 * 25 * 3, 0.0);
  const std::string wrongShape = dir.file("wrong.npy"), shortRun = dir.file("short.npy");
  writeNpy(wrongShape, {24, 3}, zeros.data());
  writeNpy(shortRun, {3, 25, 3}, zeros.data());
  const nlohmann::json point = {
      {"step", 2}, {"vertices", {1, 2}}, {"positions", {{0, 0, 0}, {0, 0, 0}}}};
  auto keypoints = [&](const nlohmann::json& change) {
    nlohmann::json entry = point;
    entry.update(change);
    for (auto it = change.begin(); it != change.end(); ++it)
      if (it.value().is_null()) entry.erase(it.key());  // null removes a key
    return nlohmann::json{{"keypoints", {{"points", {entry}}}}};
  };
  auto hemline = [](const nlohmann::json& change) {
    nlohmann::json term = {{"vertices", {20, 24}}, {"height", 0.8}};
    term.update(change);
    return nlohmann::json{{"hemline", term}};
  };
  const std::string k = "task.loss.keypoints.points.0";
  const BadLoss cases[] = {
      {"VertexOutOfRange", keypoints({{"vertices", {1, 25}}}), k + ".vertices.1", "out of range"},
      {"StepOutOfRange", keypoints({{"step", 7}}), k + ".step", "in [0, 6]"},
      {"NegativeStep", keypoints({{"step", -1}}), k + ".step", "in [0, 6]"},
      {"PositionCount", keypoints({{"positions", {{0, 0, 0}}}}), k + ".positions",
       "one [x, y, z] per listed vertex"},
      {"PositionsAndTarget", keypoints({{"target", shortRun}}), k, "give exactly one"},
      {"NoPoints",
       {{"keypoints", {{"points", nlohmann::json::array()}}}},
       "task.loss.keypoints.points",
       "at least one"},
      {"UnknownKey", keypoints({{"time", 0.1}}), k + ".time", "unknown key"},
      {"BadWeight", keypoints({{"weight", -1.0}}), k + ".weight", ""},
      {"HemlineNoTarget",
       {{"hemline", {{"vertices", {20}}}}},
       "task.loss.hemline",
       "needs a target"},
      {"HemlineVertex", hemline({{"vertices", {20, 99}}}), "task.loss.hemline.vertices.1",
       "out of range"},
      {"HemlineStep", hemline({{"steps", {6, 9}}}), "task.loss.hemline.steps.1", "in [0, 6]"},
      {"HemlineBothTargets", hemline({{"apex_angle_deg", 100.0}}),
       "task.loss.hemline.apex_angle_deg", "not both"},
      {"HemlineApexAngle",
       {{"hemline",
         {{"vertices", {20}},
          {"apex_angle_deg", 180.0},
          {"apex_height", 1.0},
          {"slant_length", 0.5}}}},
       "task.loss.hemline.apex_angle_deg",
       "strictly between"},
      {"HemlineApexIncomplete",
       {{"hemline", {{"vertices", {20}}, {"apex_angle_deg", 100.0}}}},
       "task.loss.hemline",
       "missing required key 'apex_height'"},
      {"HemlineUp", hemline({{"up", {0, 0, 0}}}), "task.loss.hemline.up", "nonzero"},
  };
  for (const BadLoss& c : cases) {
    SCOPED_TRACE(c.name);
    nlohmann::json doc = test::windClothScene(4, 6);
    doc["task"] = {{"loss", c.loss}};
    try {
      test::parse(doc);
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), c.path);
      EXPECT_NE(e.reason().find(c.phrase), std::string::npos) << e.reason();
    }
  }
  const BadLoss files[] = {
      {"WrongShape", keypoints({{"positions", nullptr}, {"target", wrongShape}}), k + ".target",
       "expected [states, 25, 3] or [25, 3]"},
      {"TooFewStates", keypoints({{"positions", nullptr}, {"step", 5}, {"target", shortRun}}),
       k + ".target", "step 5 needs at least 6"},
      {"Missing", keypoints({{"positions", nullptr}, {"target", dir.file("none.npy")}}),
       k + ".target", "not found"},
  };
  for (const BadLoss& c : files) {
    SCOPED_TRACE(c.name);
    nlohmann::json doc = test::windClothScene(4, 6);
    doc["task"] = {{"loss", c.loss}};
    const Scene scene = test::parse(doc);
    try {
      TaskLoss loss(scene);
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), c.path);
      EXPECT_NE(e.reason().find(c.phrase), std::string::npos) << e.reason();
    }
  }
}

}  // namespace
}  // namespace weft
