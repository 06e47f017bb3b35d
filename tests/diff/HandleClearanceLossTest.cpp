// task.loss.handle_clearance (diff/HandleClearanceLoss.h): its value against hand-computed
// penetrations, its parameter gradient against finite differences of that value (static and
// moving obstacles), the adjoint gradient of a task that has it beside a keypoint term, and the
// errors of a term that cannot work.

#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/core/Error.h>
#include <weft/diff/HandleClearanceLoss.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

const std::string kSpline = "cloths.0.attachments.1.trajectory.hermite.";

Vec3 vertexSix(const nlohmann::json& doc) {
  return test::parse(doc).cloths[0].mesh.vertices.row(6).transpose();
}

nlohmann::json json3(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json sphere(const Vec3& centre, double radius) {
  nlohmann::json shape;
  shape["center"] = json3(centre);
  shape["radius"] = radius;
  nlohmann::json obstacle;
  obstacle["sphere"] = shape;
  return obstacle;
}

// A handle held still (keyframes at offset 0) against a sphere whose surface is `depth` beyond its
// target: the term is weight * N * h * (margin + depth)^2, zero once the sphere is out of reach.
TEST(HandleClearanceLoss, ValueIsTheTimeIntegralOfTheSquaredPenetration) {
  nlohmann::json doc = test::handleScene(20);
  doc["cloths"][0]["attachments"][1]["trajectory"] = {
      {"keyframes", {{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}}}}};
  const Vec3 p = vertexSix(doc);
  const double radius = 0.05, weight = 3.0, margin = 0.004;
  struct Case {
    double centreDistance, penetration;
  };
  // Inside by 1 cm; outside by 1 mm (within the margin); outside by 1 cm (beyond it).
  for (const Case c : {Case{0.04, margin + 0.01}, Case{0.051, margin - 0.001}, Case{0.06, 0.0}}) {
    SCOPED_TRACE(c.centreDistance);
    doc["obstacles"] =
        nlohmann::json::array({sphere(p + Vec3(0.0, 0.0, c.centreDistance), radius)});
    const Scene scene = test::parse(doc);
    const HandleClearanceLoss loss(weight, margin);
    EXPECT_NEAR(loss.value(scene), weight * 20 * 0.01 * c.penetration * c.penetration, 1e-15);
  }
}

// dL/dtheta of every spline component against central differences of the value, with the spline
// passing through a sphere and a capsule that rotates about the vertical axis (the normal is
// carried back to the world frame).
TEST(HandleClearanceLoss, ParameterGradientMatchesFiniteDifferences) {
  nlohmann::json doc = test::handleScene(25);
  const Vec3 p = vertexSix(doc);
  nlohmann::json capsule = {{"capsule",
                             {{"a", json3(p + Vec3(-0.02, 0.035, 0.052))},
                              {"b", json3(p + Vec3(0.06, 0.035, 0.052))},
                              {"radius", 0.015}}}};
  // Turning about its own centre, near which the spline passes at t = 0.1 s.
  nlohmann::json rotate = {{"center", json3(p + Vec3(0.02, 0.035, 0.052))},
                           {"axis", {0.0, 1.0, 0.0}},
                           {"degrees_per_second", 360.0}};
  nlohmann::json still = nlohmann::json::array();
  still.push_back({{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}});
  capsule["motion"] = {{"keyframes", still}, {"rotate", rotate}};
  doc["obstacles"] = nlohmann::json::array({sphere(p + Vec3(0.035, 0.025, 0.09), 0.03), capsule});
  const Scene scene = test::parse(doc);
  std::vector<std::string> paths;
  for (int knot = 0; knot < 3; ++knot)
    for (int c = 0; c < 3; ++c) {
      if (knot > 0)
        paths.push_back(kSpline + "points." + std::to_string(knot) + "." + std::to_string(c));
      paths.push_back(kSpline + "tangents." + std::to_string(knot) + "." + std::to_string(c));
    }
  paths.push_back("cloths.0.material.stretch");  // the term does not depend on it
  const ParameterSet parameters = ParameterSet::fromPaths(scene, paths);
  const HandleClearanceLoss loss(50.0, 0.005);
  ASSERT_GT(loss.value(scene), 0.0);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(parameters.size());
  loss.addParameterGradient(scene, parameters.parameters(), gradient);
  const Eigen::VectorXd values = parameters.values(scene);
  double largest = 0.0;
  for (int k = 0; k < parameters.size(); ++k) largest = std::max(largest, std::abs(gradient[k]));
  ASSERT_GT(largest, 0.0);
  const double eps = 1e-6;
  for (int k = 0; k < parameters.size(); ++k) {
    SCOPED_TRACE(paths[k]);
    Eigen::VectorXd plus = values, minus = values;
    plus[k] += eps;
    minus[k] -= eps;
    const double fd = (loss.value(parameters.withValues(scene, plus)) -
                       loss.value(parameters.withValues(scene, minus))) /
                      (2.0 * eps);
    EXPECT_NEAR(gradient[k], fd, 1e-6 * largest) << "analytic " << gradient[k] << " fd " << fd;
  }
  EXPECT_EQ(gradient[parameters.size() - 1], 0.0);
}

// Beside a keypoint term, through `weft gradcheck`'s machinery: the adjoint gradient is the
// states' part plus the term's direct part. The sphere stays just outside the handle's path
// (within the margin), so the cloth never touches it and the run needs no contact.
TEST(HandleClearanceLoss, AdjointGradientOfATaskWithTheTermMatchesFiniteDifferences) {
  nlohmann::json doc = test::handleScene(20);
  const Vec3 p = vertexSix(doc);
  doc["obstacles"] = nlohmann::json::array({sphere(p + Vec3(0.045, 0.05, 0.08), 0.01)});
  doc["task"] = {{"loss",
                  {{"keypoints",
                    {{"points",
                      {{{"step", 10},
                        {"vertices", {48, 24}},
                        {"positions", {{0.25, 0.8, 0.05}, {0.0, 1.0, 0.1}}}},
                       {{"step", 20}, {"vertices", {42}}, {"positions", {{-0.2, 0.85, 0.1}}}}}}}},
                   {"handle_clearance", {{"weight", 2000.0}, {"margin", 0.03}}}}},
                 {"parameters",
                  {kSpline + "points.1.0", kSpline + "points.1.1", kSpline + "points.2.2",
                   kSpline + "tangents.1.0", kSpline + "tangents.1.1"}}};
  const Scene scene = test::parse(doc);
  const TaskLoss loss(scene);
  ASSERT_TRUE(loss.clearance());
  ASSERT_GT(loss.clearance()->value(scene), 0.0);
  test::expectAdjointMatchesFiniteDifferences(scene);
}

TEST(HandleClearanceLoss, ATermThatCannotWorkIsAnInputErrorNamingItsPath) {
  nlohmann::json doc = test::handleScene(5);
  doc["task"] = {{"loss", {{"handle_clearance", {{"weight", 1.0}}}}},
                 {"parameters", {kSpline + "points.1.0"}}};
  // No obstacle: the term would be zero whatever the parameters.
  try {
    TaskLoss loss(test::parse(doc));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), "task.loss.handle_clearance");
    EXPECT_NE(e.reason().find("needs a handle attachment and an obstacle"), std::string::npos)
        << e.reason();
  }
  doc["obstacles"] = nlohmann::json::array({sphere(Vec3::Zero(), 0.1)});
  struct Bad {
    nlohmann::json term;
    std::string path;
  };
  for (const Bad& b : {Bad{{{"margin", -0.01}}, "task.loss.handle_clearance.margin"},
                       Bad{{{"weight", 0.0}}, "task.loss.handle_clearance.weight"},
                       Bad{{{"depth", 0.01}}, "task.loss.handle_clearance.depth"}}) {
    SCOPED_TRACE(b.term.dump());
    doc["task"]["loss"]["handle_clearance"] = b.term;
    try {
      test::parse(doc);
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), b.path);
    }
  }
}

}  // namespace
}  // namespace weft
