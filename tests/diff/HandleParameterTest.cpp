// Handle trajectory parameters (DiffCloth Appendix B, Hat and Sock: the spline's tangents and
// end point): the interpolation weights the adjoint chains through, the JSON paths that resolve
// to them, and the adjoint gradient of a small cloth pulled by a handle against central finite
// differences of the task loss.

#include <app/CliSupport.h>
#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/SceneParameter.h>
#include <weft/scene/HandleTrajectory.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace weft {
namespace {

using Control = HandleTrajectory::Control;
using test::TempDir;

HandleTrajectory hermite() {
  HandleTrajectory t;
  t.kind = HandleTrajectory::Kind::Hermite;
  t.times = {0.1, 0.4, 1.0};
  t.offsets = {Vec3(0, 0, 0), Vec3(0.3, -0.2, 0.1), Vec3(0.5, 0.4, -0.3)};
  t.tangents = {Vec3(1, 0, 0), Vec3(-0.5, 2, 0.3), Vec3(0, 0, 1)};
  return t;
}

HandleTrajectory keyframes() {
  HandleTrajectory t = hermite();
  t.kind = HandleTrajectory::Kind::Keyframes;
  t.tangents.clear();
  return t;
}

// d offset(t) / d control[knot] by central differences of offset() itself (the offset is linear
// in its knot values, so the difference is exact up to round-off).
Vec3 finiteDifference(HandleTrajectory t, double time, Control control, int knot, int component) {
  const double step = 1e-3;
  std::vector<Vec3>& values = control == Control::Offset ? t.offsets : t.tangents;
  values[knot][component] += step;
  const Vec3 plus = t.offset(time);
  values[knot][component] -= 2 * step;
  const Vec3 minus = t.offset(time);
  return (plus - minus) / (2 * step);
}

TEST(HandleTrajectory, ControlWeightsAreTheDerivativesOfTheOffset) {
  // Before, inside and after the key range, on knots and between them.
  for (const HandleTrajectory& t : {hermite(), keyframes()}) {
    const bool isHermite = t.kind == HandleTrajectory::Kind::Hermite;
    for (double time : {0.0, 0.1, 0.25, 0.4, 0.77, 1.0, 1.5}) {
      for (Control control : {Control::Offset, Control::Tangent}) {
        if (control == Control::Tangent && !isHermite) {
          for (int knot = 0; knot < 3; ++knot) EXPECT_EQ(t.controlWeight(time, control, knot), 0.0);
          continue;
        }
        for (int knot = 0; knot < 3; ++knot) {
          SCOPED_TRACE(std::to_string(isHermite) + " t=" + std::to_string(time) + " knot " +
                       std::to_string(knot) +
                       (control == Control::Offset ? " offset" : " tangent"));
          const double w = t.controlWeight(time, control, knot);
          for (int c = 0; c < 3; ++c) {
            const Vec3 fd = finiteDifference(t, time, control, knot, c);
            EXPECT_NEAR(fd[c], w, 1e-12);
            EXPECT_NEAR(fd.norm(), std::abs(w), 1e-12);  // componentwise: no cross terms
          }
        }
      }
    }
  }
  // The held end point carries the whole offset.
  EXPECT_EQ(hermite().controlWeight(2.0, Control::Offset, 2), 1.0);
  EXPECT_EQ(hermite().controlWeight(-1.0, Control::Offset, 0), 1.0);
}

const std::string kHandle = "cloths.0.attachments.1.";

TEST(HandleParameter, ResolvesTheTrajectoryKnotsAndStiffness) {
  nlohmann::json doc = test::handleScene(5);
  const nlohmann::json keys = nlohmann::json::array(
      {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.1}, {"offset", {0, 1, 0}}}});
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {3}}, {"kind", "handle"}, {"trajectory", {{"keyframes", keys}}}});
  const Scene scene = test::parse(doc);
  using Kind = SceneParameter::Kind;
  struct Case {
    std::string path;
    Kind kind;
    int index, knot, component;
  };
  const Case cases[] = {
      {kHandle + "trajectory.hermite.points.2.1", Kind::HandleOffset, 1, 2, 1},
      {kHandle + "trajectory.hermite.tangents.0.2", Kind::HandleTangent, 1, 0, 2},
      {"cloths.0.attachments.2.trajectory.keyframes.1.offset.0", Kind::HandleOffset, 2, 1, 0},
      {kHandle + "stiffness", Kind::AttachmentStiffness, 1, -1, -1},
      {"cloths.0.attachments.0.stiffness", Kind::AttachmentStiffness, 0, -1, -1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    const SceneParameter p = resolveSceneParameter(scene, c.path, "--param");
    EXPECT_EQ(p.kind, c.kind);
    EXPECT_EQ(p.cloth, 0);
    EXPECT_EQ(p.index, c.index);
    EXPECT_EQ(p.knot, c.knot);
    EXPECT_EQ(p.component, c.component);
  }
  // Knot times are not differentiable (a knot crossing a step time is a kink); neither is a
  // stiffness the file leaves to its default.
  for (const std::string& path : std::vector<std::string>{
           kHandle + "trajectory.hermite.times.1", "cloths.0.attachments.2.stiffness",
           "cloths.0.attachments.2.trajectory.keyframes.1.time",
           kHandle + "trajectory.hermite.points.3.0"}) {
    SCOPED_TRACE(path);
    try {
      resolveSceneParameter(scene, path, "--param " + path);
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), "--param " + path);
    }
  }
}

// The Hat task in miniature: a final-frame target made by the same scene with another spline.
TEST(HandleParameter, SplineGradientsMatchFiniteDifferencesForAFinalFrameTarget) {
  TempDir dir;
  nlohmann::json doc = test::handleScene();
  nlohmann::json targetDoc = doc;
  nlohmann::json& spline = targetDoc["cloths"][0]["attachments"][1]["trajectory"]["hermite"];
  spline["points"][2] = {0.08, 0.0, 0.15};
  spline["tangents"][1] = {0.2, 0.2, 0.6};
  const std::string target = test::writeTargetTrajectory(targetDoc, dir.file("target.npy"));
  const std::string s = kHandle + "trajectory.hermite.";
  test::addTask(doc, "final", target,
                {s + "points.2.0", s + "points.2.1", s + "points.2.2", s + "points.1.2",
                 s + "tangents.0.0", s + "tangents.1.1", s + "tangents.1.2", s + "tangents.2.2",
                 kHandle + "stiffness", "cloths.0.attachments.0.stiffness"});
  test::expectAdjointMatchesFiniteDifferences(test::parse(doc));
}

// The Sock task in miniature: keypoints at the middle and the end of the run, on keyframes.
TEST(HandleParameter, KeyframeGradientsMatchFiniteDifferencesForKeypoints) {
  nlohmann::json doc = test::handleScene(20);
  doc["cloths"][0]["attachments"][1]["trajectory"] = {
      {"keyframes",
       {{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}},
        {{"time", 0.08}, {"offset", {0.03, 0.01, 0.06}}},
        {{"time", 0.15}, {"offset", {0.05, 0.04, 0.1}}}}}};
  const std::string k = kHandle + "trajectory.keyframes.";
  doc["task"] = {
      {"loss",
       {{"keypoints",
         {{"points",
           {{{"step", 10},
             {"vertices", {48, 24}},
             {"positions", {{0.25, 0.8, 0.05}, {0.0, 1.0, 0.1}}}},
            {{"step", 20},
             {"vertices", {42}},
             {"positions", {{-0.2, 0.85, 0.1}}},
             {"weight", 3.0}}}}}}}},
      {"parameters", {k + "1.offset.0", k + "1.offset.2", k + "2.offset.1", k + "2.offset.2"}}};
  test::expectAdjointMatchesFiniteDifferences(test::parse(doc));
}

// `weft gradcheck` resolves the new parameters and builds the new losses with no option of its
// own: the scene's task lists spline tangents, end point, handle stiffness and the material.
TEST(HandleParameter, GradcheckCliChecksTheSceneTask) {
  const std::string scene = test::dataFile("scenes/handle_keypoints.json");
  const auto r = test::runWeft({"gradcheck", scene, "--json", "--threads", "1"});
  ASSERT_EQ(r.exitCode, 0) << test::describe(r);
  const nlohmann::json list = nlohmann::json::parse(r.out);
  ASSERT_EQ(list.size(), 10u);
  for (const auto& e : list) {
    SCOPED_TRACE(e.dump());
    EXPECT_NE(e["adjoint"].get<double>(), 0.0);
    EXPECT_LT(e["relative_error"].get<double>(), 1e-4);
  }
}

TEST(HandleParameter, GradcheckCliBadLossInputExitsTwo) {
  const std::string scene = test::dataFile("scenes/handle_keypoints.json");
  test::expectBadInput(
      "gradcheck", {scene, "--set", "task.loss.keypoints.points.1.step=26"},
      "handle_keypoints.json: task.loss.keypoints.points.1.step: ", "integer in [0, 25]");
  test::expectBadInput("gradcheck", {scene, "--set", "task.loss.hemline.vertices.3=49"},
                       "handle_keypoints.json: task.loss.hemline.vertices.3: ", "out of range");
  test::expectBadInput(
      "gradcheck", {scene, "--param", "cloths.0.attachments.1.trajectory.hermite.times.1"},
      "--param cloths.0.attachments.1.trajectory.hermite.times.1: ", "not differentiable");
}

}  // namespace
}  // namespace weft
