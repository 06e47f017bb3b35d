// The analytic obstacle shapes (plane, sphere, capsule, box, cylinder) against closed-form
// signed distances computed here independently (by clamping to the solid), their normals
// against central finite differences of the distance (the normal is the distance gradient away
// from the medial axis), their closest points, and the `reach` early-out.

#include <weft/contact/BoxShape.h>
#include <weft/contact/CapsuleShape.h>
#include <weft/contact/CylinderShape.h>
#include <weft/contact/PlaneShape.h>
#include <weft/contact/SphereShape.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>

namespace weft {
namespace {

struct ShapeCase {
  const char* name;
  std::function<std::unique_ptr<ObstacleShape>()> make;
  // Closed-form signed distance; `kink` gets how close p is to a place where the distance is
  // not differentiable (medial axis inside, or the axis of a round shape), in m.
  std::function<double(const Vec3&, double& kink)> distance;
  Vec3 lower, upper;  // where to sample
};

void PrintTo(const ShapeCase& c, std::ostream* os) { *os << c.name; }

const Vec3 kPlanePoint(0.1, -0.2, 0.3);
const Vec3 kPlaneNormal = Vec3(0.3, 1.0, -0.2).normalized();
const Vec3 kCentre(0.2, 0.1, -0.1);
const Vec3 kA(-0.3, 0.0, 0.1), kB(0.4, 0.2, -0.1);
const Vec3 kHalf(0.3, 0.1, 0.2);
const Mat3 kRotation = (Eigen::AngleAxisd(0.4, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.7, Vec3::UnitY()) *
                        Eigen::AngleAxisd(0.2, Vec3::UnitX())).toRotationMatrix();

double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + s * (b - a))).norm();
}

double boxDistance(const Vec3& p, double& kink) {
  const Vec3 local = kRotation.transpose() * (p - kCentre);
  const Vec3 clamped = local.cwiseMax(-kHalf).cwiseMin(kHalf);
  const double outside = (local - clamped).norm();
  if (outside > 0.0) {
    kink = 1.0;
    return outside;
  }
  // Inside: the nearest face; the distance kinks where two faces are equally near.
  double depth[3];
  for (int k = 0; k < 3; ++k) depth[k] = kHalf[k] - std::abs(local[k]);
  std::sort(depth, depth + 3);
  kink = std::min(depth[1] - depth[0], depth[0]);
  return -depth[0];
}

double cylinderDistance(const Vec3& p, double& kink) {
  const double radius = 0.15;
  const Vec3 axis = (kB - kA).normalized();
  const double half = 0.5 * (kB - kA).norm();
  const Vec3 offset = p - 0.5 * (kA + kB);
  const double axial = offset.dot(axis), radial = (offset - axial * axis).norm();
  // The solid in (axial, radial) coordinates is the rectangle [-half, half] x [0, radius].
  const double ca = std::clamp(axial, -half, half), cr = std::min(radial, radius);
  const double outside = std::hypot(axial - ca, radial - cr);
  kink = radial;
  if (outside > 0.0) return outside;
  const double toCap = half - std::abs(axial), toSide = radius - radial;
  kink = std::min({radial, std::abs(toCap - toSide), toCap});
  return -std::min(toCap, toSide);
}

const ShapeCase kShapes[] = {
    {"Plane", [] { return std::make_unique<PlaneShape>(kPlanePoint, 3.0 * kPlaneNormal); },
     [](const Vec3& p, double& kink) {
       kink = 1.0;
       return kPlaneNormal.dot(p - kPlanePoint);
     },
     Vec3::Constant(-1.0), Vec3::Constant(1.0)},
    {"Sphere", [] { return std::make_unique<SphereShape>(kCentre, 0.4); },
     [](const Vec3& p, double& kink) {
       kink = (p - kCentre).norm();
       return (p - kCentre).norm() - 0.4;
     },
     Vec3::Constant(-1.0), Vec3::Constant(1.0)},
    {"Capsule", [] { return std::make_unique<CapsuleShape>(kA, kB, 0.15); },
     [](const Vec3& p, double& kink) {
       kink = segmentDistance(p, kA, kB);
       return segmentDistance(p, kA, kB) - 0.15;
     },
     Vec3::Constant(-1.0), Vec3::Constant(1.0)},
    {"Box", [] { return std::make_unique<BoxShape>(kCentre, kHalf, kRotation); }, boxDistance,
     Vec3::Constant(-0.6), Vec3::Constant(0.8)},
    {"Cylinder", [] { return std::make_unique<CylinderShape>(kA, kB, 0.15); }, cylinderDistance,
     Vec3::Constant(-0.7), Vec3::Constant(0.7)},
};

class AnalyticShape : public ::testing::TestWithParam<ShapeCase> {};

TEST_P(AnalyticShape, SignedDistanceNormalAndClosestPointMatchClosedForm) {
  const ShapeCase& c = GetParam();
  const auto shape = c.make();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double reach = 1e9, eps = 1e-6;
  int inside = 0, checkedNormals = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p = c.lower + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(c.upper - c.lower);
    double kink = 0.0;
    const double expected = c.distance(p, kink);
    SurfaceSample s;
    ASSERT_TRUE(shape->sample(p, reach, s)) << "at " << p.transpose();
    ASSERT_NEAR(s.distance, expected, 1e-12) << "at " << p.transpose();
    ASSERT_NEAR(s.normal.norm(), 1.0, 1e-12);
    // The closest point is p moved back along the normal by the distance, and lies on the surface.
    ASSERT_LT((s.point - (p - s.distance * s.normal)).norm(), 1e-12);
    double onSurface = 0.0;
    ASSERT_NEAR(c.distance(s.point, onSurface), 0.0, 1e-12) << "closest point of " << p.transpose();
    inside += expected < 0.0;
    if (kink < 1e-3) continue;
    // The normal is the gradient of the signed distance.
    Vec3 gradient;
    for (int d = 0; d < 3; ++d) {
      double unused = 0.0;
      const Vec3 step = eps * Vec3::Unit(d);
      gradient[d] = (c.distance(p + step, unused) - c.distance(p - step, unused)) / (2 * eps);
    }
    ASSERT_LT((gradient - s.normal).norm(), 1e-6) << "at " << p.transpose() << ": normal " << s.normal.transpose()
                                                  << ", gradient " << gradient.transpose();
    ++checkedNormals;
  }
  // The sample covered both sides of the surface.
  EXPECT_GT(inside, 15);
  EXPECT_LT(inside, 2970);
  EXPECT_GT(checkedNormals, 2500);
}

TEST_P(AnalyticShape, ReachOnlySkipsPointsFartherThanReach) {
  const ShapeCase& c = GetParam();
  const auto shape = c.make();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double reach = 0.05;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p = c.lower + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(c.upper - c.lower);
    double kink = 0.0;
    const double expected = c.distance(p, kink);
    SurfaceSample s;
    const bool found = shape->sample(p, reach, s);
    if (expected <= reach) {
      ASSERT_TRUE(found) << "distance " << expected << " at " << p.transpose();
      ASSERT_NEAR(s.distance, expected, 1e-12);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, AnalyticShape, ::testing::ValuesIn(kShapes),
                         [](const ::testing::TestParamInfo<ShapeCase>& info) { return std::string(info.param.name); });

// A node exactly at a round shape's centre still gets a unit normal and the right depth.
TEST(AnalyticShapeDegenerate, CentreOfSphereAndAxisOfCapsule) {
  SurfaceSample s;
  ASSERT_TRUE(SphereShape(kCentre, 0.4).sample(kCentre, 0.1, s));
  EXPECT_NEAR(s.distance, -0.4, 1e-15);
  EXPECT_NEAR(s.normal.norm(), 1.0, 1e-15);
  ASSERT_TRUE(CapsuleShape(kA, kB, 0.15).sample(0.5 * (kA + kB), 0.1, s));
  EXPECT_NEAR(s.distance, -0.15, 1e-15);
  EXPECT_NEAR(s.normal.norm(), 1.0, 1e-15);
  ASSERT_TRUE(CylinderShape(kA, kB, 0.15).sample(0.5 * (kA + kB), 0.1, s));
  EXPECT_NEAR(s.distance, -0.15, 1e-15);
  EXPECT_NEAR(s.normal.norm(), 1.0, 1e-15);
}

}  // namespace
}  // namespace weft
