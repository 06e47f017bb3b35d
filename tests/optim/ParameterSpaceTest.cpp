// ParameterSpace (engine/include/weft/optim/ParameterSpace.h): the coordinates optimisers work in.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/optim/ParameterSpace.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

// The wind cloth with a trajectory task over a log-scaled stiffness, a linear wind strength and
// a wind direction component that starts at 0 (scale 1).
Scene sceneWithStretch(const test::TempDir& dir, double stretch) {
  nlohmann::json doc = test::windClothScene(4, 3);
  doc["cloths"][0]["material"]["stretch"] = stretch;
  return test::withTrajectoryTask(
      dir, doc, {"cloths.0.material.stretch", "wind.strength", "wind.direction.1"});
}

TEST(ParameterSpace, TheStartMapsBackToTheScenesOwnValuesBitForBit) {
  // exp(log(500)) is 499.99999999999983: without the exact start, an optimiser's first
  // evaluation would simulate a scene one ulp away from the one written.
  ASSERT_NE(std::exp(std::log(500.0)), 500.0) << "the case this test exists for";
  test::TempDir dir;
  const Scene scene = sceneWithStretch(dir, 500.0);
  const ParameterSpace space(scene, ParameterSet::fromTask(scene));
  ASSERT_TRUE(space.parameters()[0].logScale);
  const Eigen::VectorXd start = space.initialValues();
  EXPECT_EQ(start[0], 500.0);
  const Eigen::VectorXd back = space.toValues(space.toCoordinates(start));
  for (int i = 0; i < space.size(); ++i) EXPECT_EQ(back[i], start[i]) << space.parameters()[i].path;
}

TEST(ParameterSpace, OtherCoordinatesFollowTheLogAndLinearMaps) {
  test::TempDir dir;
  const Scene scene = sceneWithStretch(dir, 500.0);
  const ParameterSpace space(scene, ParameterSet::fromTask(scene));
  const Eigen::VectorXd start = space.initialValues();
  Eigen::VectorXd z = space.toCoordinates(start);
  EXPECT_DOUBLE_EQ(z[0], std::log(500.0));
  EXPECT_DOUBLE_EQ(z[1], start[1] / std::abs(start[1]));  // value / its starting magnitude
  EXPECT_EQ(z[2], start[2]);                              // starts at 0: scale 1
  z += Eigen::VectorXd::Constant(space.size(), 0.25);
  const Eigen::VectorXd v = space.toValues(z);
  EXPECT_DOUBLE_EQ(v[0], 500.0 * std::exp(0.25));
  EXPECT_DOUBLE_EQ(v[1], start[1] + 0.25 * std::abs(start[1]));
  EXPECT_DOUBLE_EQ(v[2], start[2] + 0.25);
  // Only the coordinate that still equals the start's keeps the scene's value.
  z[0] = space.toCoordinates(start)[0];
  EXPECT_EQ(space.toValues(z)[0], 500.0);
  EXPECT_DOUBLE_EQ(space.toValues(z)[1], v[1]);
}

TEST(ParameterSpace, AHandleKnotsTaskBoxSetsItsScaleNotItsStartingValue) {
  // Two components of one spline knot in the same [-0.5, 0.5] m box, starting at 0.02 and 0.03
  // m: both are value / 0.5, so one unit moves either by 0.5 m (by their starts, 0.02 and
  // 0.03). A tangent in [-1, 1] m/s: value / 1 (its start is 0.2). A knot with a half-open box,
  // and the wind strength (a magnitude, not a path coordinate) even with a finite box, keep
  // their starting magnitudes.
  test::TempDir dir;
  nlohmann::json doc = test::handleScene(3);
  const std::string knot = "cloths.0.attachments.1.trajectory.hermite.";
  test::addTask(doc, "trajectory", test::writeTargetTrajectory(doc, dir.file("t.npy")),
                {knot + "points.1.0", knot + "points.1.2", knot + "tangents.0.0",
                 knot + "points.1.1", "wind.strength"});
  const double strength = doc["wind"]["strength"].get<double>();
  doc["task"]["bounds"] = {{knot + "points.1.0", {-0.5, 0.5}},
                           {knot + "points.1.2", {-0.5, 0.5}},
                           {knot + "tangents.0.0", {-1.0, 1.0}},
                           {knot + "points.1.1", {nullptr, 1.0}},
                           {"wind.strength", {0.0, 10.0 * strength}}};
  const Scene scene = test::parse(doc);
  const ParameterSpace space(scene, ParameterSet::fromTask(scene));
  EXPECT_EQ(space.linearScale(0), 0.5);
  EXPECT_EQ(space.linearScale(1), 0.5);
  EXPECT_EQ(space.linearScale(2), 1.0);
  EXPECT_EQ(space.linearScale(3), 0.03);      // half-open box: its start
  EXPECT_EQ(space.linearScale(4), strength);  // not a knot: its start
  const Eigen::VectorXd z = space.toCoordinates(space.initialValues());
  EXPECT_DOUBLE_EQ(z[0], 0.02 / 0.5);
  EXPECT_DOUBLE_EQ(space.lowerCoordinates()[0], -1.0);
  EXPECT_DOUBLE_EQ(space.upperCoordinates()[1], 1.0);
  EXPECT_DOUBLE_EQ(space.upperCoordinates()[4], 10.0);
  Eigen::VectorXd step = z;
  step[0] += 1.0, step[1] += 1.0;
  const Eigen::VectorXd v = space.toValues(step);
  EXPECT_DOUBLE_EQ(v[0], 0.02 + 0.5);
  EXPECT_DOUBLE_EQ(v[1], 0.05 + 0.5);
  // The chain rule with the same scales.
  const Eigen::VectorXd g = Eigen::VectorXd::Ones(space.size());
  const Eigen::VectorXd gz = space.gradientToCoordinates(z, g);
  EXPECT_DOUBLE_EQ(gz[0], 0.5);
  EXPECT_DOUBLE_EQ(gz[4], strength);
  EXPECT_DOUBLE_EQ(space.gradientToValues(z, gz)[3], 1.0);
}

}  // namespace
}  // namespace weft
