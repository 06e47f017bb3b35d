// The task losses: values and state gradients as documented, and targets checked against the
// scene (naming the JSON path of the term).

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/FinalFrameLoss.h>
#include <weft/diff/TaskLoss.h>
#include <weft/diff/TrajectoryLoss.h>
#include <weft/io/Npy.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

using test::TempDir;

Trajectory twoStates(const NodeMatrix& a, const NodeMatrix& b, const NodeMatrix& c) {
  Trajectory t;
  t.positions = {a, b, c};
  return t;
}

TEST(TrajectoryLoss, SumsSquaredDistancesOverStatesOneToN) {
  const NodeMatrix zero = NodeMatrix::Zero(2, 3);
  NodeMatrix b = zero, c = zero;
  b(0, 0) = 1.0;
  c(1, 2) = 2.0;
  const Trajectory t = twoStates(NodeMatrix::Constant(2, 3, 5.0), b, c);  // state 0 is ignored
  const TrajectoryLoss all({zero, zero, zero}, {}, 0.5);
  EXPECT_DOUBLE_EQ(all.value(t), 0.5 * (1.0 + 4.0));
  std::vector<NodeMatrix> g(3, zero);
  all.addGradient(t, g);
  EXPECT_TRUE(g[0].isZero());
  EXPECT_DOUBLE_EQ(g[1](0, 0), 1.0);
  EXPECT_DOUBLE_EQ(g[2](1, 2), 2.0);
  const TrajectoryLoss chosen({zero, zero, zero}, {1}, 1.0);
  EXPECT_DOUBLE_EQ(chosen.value(t), 4.0);
}

TEST(FinalFrameLoss, LooksAtTheLastStateOnly) {
  const NodeMatrix zero = NodeMatrix::Zero(2, 3);
  NodeMatrix c = zero;
  c(0, 1) = 3.0;
  c(1, 1) = 1.0;
  const Trajectory t = twoStates(zero, NodeMatrix::Constant(2, 3, 7.0), c);
  const FinalFrameLoss loss(zero, {0}, 2.0);
  EXPECT_DOUBLE_EQ(loss.value(t), 18.0);
  std::vector<NodeMatrix> g(3, zero);
  loss.addGradient(t, g);
  EXPECT_DOUBLE_EQ(g[2](0, 1), 12.0);
  EXPECT_DOUBLE_EQ(g[2](1, 1), 0.0);
  EXPECT_TRUE(g[1].isZero());
}

void expectInputError(const nlohmann::json& doc, const std::string& path,
                      const std::string& phrase) {
  const Scene scene = test::parse(doc);
  try {
    TaskLoss loss(scene);
    FAIL() << "expected an InputError at " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_NE(e.reason().find(phrase), std::string::npos) << e.reason();
  }
}

TEST(TaskLoss, ChecksTargetsAgainstTheScene) {
  TempDir dir;
  nlohmann::json doc = test::windClothScene(4, 5);  // 25 vertices, 5 steps
  expectInputError(doc, "task", "no task");
  const std::vector<double> data(3 * 25 * 3, 0.0);
  writeNpy(dir.file("short.npy"), {3, 25, 3}, data.data());
  writeNpy(dir.file("wrong.npy"), {3, 24, 3}, data.data());
  test::addTask(doc, "trajectory", dir.file("short.npy"), {});
  expectInputError(doc, "task.loss.trajectory.target", "needs 6");
  test::addTask(doc, "final", dir.file("wrong.npy"), {});
  expectInputError(doc, "task.loss.final.target", "expected [states, 25, 3]");
  test::addTask(doc, "final", dir.file("missing.npy"), {});
  expectInputError(doc, "task.loss.final.target", "not found");
  test::addTask(doc, "final", dir.file("short.npy"), {});
  doc["task"]["loss"]["final"]["vertices"] = {3, 25};
  expectInputError(doc, "task.loss.final.vertices.1", "vertex index");
}

}  // namespace
}  // namespace weft
