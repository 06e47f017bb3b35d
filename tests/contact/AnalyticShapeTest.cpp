// The analytic obstacle shapes (plane, sphere, capsule, box, cylinder) against closed-form
// signed distances computed here independently (by clamping to the solid), their normals
// against central finite differences of the distance (the normal is the distance gradient away
// from the medial axis), their closest points, and the `reach` early-out; and the box's contact
// face and the cylinder's contact surface for a point its relative motion took inside it
// (BoxShape::sampleMoved, CylinderShape::sampleMoved).

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

void PrintTo(const ShapeCase& c, std::ostream* os) {
  *os << c.name;
}

const Vec3 kPlanePoint(0.1, -0.2, 0.3);
const Vec3 kPlaneNormal = Vec3(0.3, 1.0, -0.2).normalized();
const Vec3 kCentre(0.2, 0.1, -0.1);
const Vec3 kA(-0.3, 0.0, 0.1), kB(0.4, 0.2, -0.1);
const Vec3 kHalf(0.3, 0.1, 0.2);
const Mat3 kRotation =
    (Eigen::AngleAxisd(0.4, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.7, Vec3::UnitY()) *
     Eigen::AngleAxisd(0.2, Vec3::UnitX()))
        .toRotationMatrix();

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
    ASSERT_LT((gradient - s.normal).norm(), 1e-6)
        << "at " << p.transpose() << ": normal " << s.normal.transpose() << ", gradient "
        << gradient.transpose();
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
                         [](const ::testing::TestParamInfo<ShapeCase>& info) {
                           return std::string(info.param.name);
                         });

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

namespace weft {
namespace {

// sampleMoved's other cases: for random points p and path starts `from` (drawn by `draw`), unless
// p is inside and `from` outside, the answer is sample(p)'s. Counts the outside and inside points
// checked.
void expectSampleMovedIsSampleOtherwise(
    const ObstacleShape& shape, const std::function<bool(const Vec3&)>& within,
    const std::function<void(std::mt19937&, Vec3&, Vec3&)>& draw, unsigned seed) {
  std::mt19937 rng(seed);
  int outside = 0, inside = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    Vec3 p, from;
    draw(rng, p, from);
    const bool pInside = within(p);
    if (pInside && !within(from)) continue;
    SurfaceSample a, b;
    const bool hitA = shape.sample(p, 1.0, a), hitB = shape.sampleMoved(p, from, 1.0, b);
    ASSERT_EQ(hitA, hitB);
    EXPECT_EQ(a.distance, b.distance);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.point, b.point);
    (pInside ? inside : outside)++;
  }
  EXPECT_GT(outside, 100);
  EXPECT_GT(inside, 20);
}

// BoxShape::sampleMoved: a point inside the box that came from outside gets the face its path
// crossed, not the nearest face; everything else is sample()'s answer. The box is rotated, and
// the points are given in its body frame (x = 0.1 is a side face, y = -0.05 the bottom).
class BoxEntryFace : public ::testing::Test {
 protected:
  const Vec3 half{0.1, 0.05, 0.3};
  const BoxShape box{kCentre, half, kRotation};
  Vec3 world(double x, double y, double z) const { return kCentre + kRotation * Vec3(x, y, z); }
};

TEST_F(BoxEntryFace, SideEntryNearTheBottomEdgeGetsTheSideNormal) {
  // A node 1 mm above the bottom face, 1 mm outside the side face at the start; the box moves
  // 10 mm towards it: relative to the box it ends 9 mm inside the side, still 1 mm above the
  // bottom (a box standing on a floor sweeping over a node lying on the floor).
  const Vec3 from = world(0.101, -0.049, 0.1), p = world(0.091, -0.049, 0.1);
  SurfaceSample nearest, entered;
  ASSERT_TRUE(box.sample(p, 0.01, nearest));
  EXPECT_LT((nearest.normal + kRotation.col(1)).norm(), 1e-12) << "the nearest face is the bottom";
  ASSERT_TRUE(box.sampleMoved(p, from, 0.01, entered));
  EXPECT_LT((entered.normal - kRotation.col(0)).norm(), 1e-12);
  EXPECT_NEAR(entered.distance, -0.009, 1e-12);
  EXPECT_LT((entered.point - world(0.1, -0.049, 0.1)).norm(), 1e-12);
}

TEST_F(BoxEntryFace, TheFaceCrossedNotAPreferredOne) {
  // Up through the bottom, 1 mm inside the side's slab: the bottom normal, although the side is
  // the nearest face at the end.
  SurfaceSample s;
  ASSERT_TRUE(box.sampleMoved(world(0.099, -0.04, 0.0), world(0.099, -0.06, 0.0), 0.01, s));
  EXPECT_LT((s.normal + kRotation.col(1)).norm(), 1e-12);
  EXPECT_NEAR(s.distance, -0.01, 1e-12);
  // Diagonally past the edge: outside both slabs at the start; x = 0.1 is crossed at 20% of the
  // path (the point is then still under the box), y = -0.05 at 67%: in through the bottom.
  ASSERT_TRUE(box.sampleMoved(world(0.092, -0.045, 0.0), world(0.102, -0.06, 0.0), 0.01, s));
  EXPECT_LT((s.normal + kRotation.col(1)).norm(), 1e-12);
  EXPECT_NEAR(s.distance, -0.005, 1e-12);
  // The mirrored path (x -> -x, y -> -y): in through the top after the -x side's slab.
  ASSERT_TRUE(box.sampleMoved(world(-0.092, 0.045, 0.0), world(-0.102, 0.06, 0.0), 0.01, s));
  EXPECT_LT((s.normal - kRotation.col(1)).norm(), 1e-12);
  // Swap which slab is entered last: now the side (-x) at 47%, the top at 29%.
  ASSERT_TRUE(box.sampleMoved(world(-0.092, 0.045, 0.0), world(-0.107, 0.052, 0.0), 0.01, s));
  EXPECT_LT((s.normal + kRotation.col(0)).norm(), 1e-12);
  EXPECT_NEAR(s.distance, -0.008, 1e-12);
}

TEST_F(BoxEntryFace, OutsideOrAlreadyInsideIsTheSignedDistanceSample) {
  // Outside the box (every node resting in a skin) the frame is the smooth distance gradient
  // whatever the path; a path that starts inside has no entry face: the nearest face.
  expectSampleMovedIsSampleOtherwise(
      box,
      [&](const Vec3& q) {
        return ((kRotation.transpose() * (q - kCentre)).cwiseAbs() - half).maxCoeff() <= 0.0;
      },
      [](std::mt19937& rng, Vec3& p, Vec3& from) {
        std::uniform_real_distribution<double> u(-0.4, 0.4);
        p = kCentre + Vec3(u(rng), u(rng), u(rng));
        from = kCentre + 0.3 * Vec3(u(rng), u(rng), u(rng));
      },
      7);
}

// CylinderShape::sampleMoved, the same rule for a cylinder whose flat cap may lie flush with a
// floor: a point inside that came from outside gets the surface (side or cap) its path crossed.
// The cylinder's axis is tilted; points are given in its frame: (radial x, radial y, axial), the
// caps at axial +-0.1 and the side at radius 0.1.
class CylinderEntrySurface : public ::testing::Test {
 protected:
  const Vec3 axis = kRotation.col(2), radialX = kRotation.col(0), radialY = kRotation.col(1);
  const CylinderShape cylinder{kCentre - 0.1 * axis, kCentre + 0.1 * axis, 0.1};
  Vec3 world(double x, double y, double a) const {
    return kCentre + x * radialX + y * radialY + a * axis;
  }
};

TEST_F(CylinderEntrySurface, SideEntryNearTheCapGetsTheSideNormal) {
  // 1 mm above the bottom cap, 1 mm outside the side at the start; 10 mm across the side: the
  // cylinder standing on a floor sweeping over a node lying there.
  const Vec3 from = world(0.101, 0.0, -0.099), p = world(0.091, 0.0, -0.099);
  SurfaceSample nearest, entered;
  ASSERT_TRUE(cylinder.sample(p, 0.01, nearest));
  EXPECT_LT((nearest.normal + axis).norm(), 1e-12) << "the nearest surface is the bottom cap";
  ASSERT_TRUE(cylinder.sampleMoved(p, from, 0.01, entered));
  EXPECT_LT((entered.normal - radialX).norm(), 1e-12) << entered.normal.transpose();
  EXPECT_NEAR(entered.distance, -0.009, 1e-12);
  EXPECT_LT((entered.point - world(0.1, 0.0, -0.099)).norm(), 1e-12);
}

TEST_F(CylinderEntrySurface, TheSurfaceCrossedNotAPreferredOne) {
  SurfaceSample s;
  // Up through the bottom cap 1 mm inside the rim: the cap's normal, although the side is the
  // nearest surface at the end.
  ASSERT_TRUE(cylinder.sampleMoved(world(0.0, 0.099, -0.09), world(0.0, 0.099, -0.11), 0.01, s));
  EXPECT_LT((s.normal + axis).norm(), 1e-12);
  EXPECT_NEAR(s.distance, -0.01, 1e-12);
  // Diagonally past the rim, outside both at the start: the side (radius 0.1) is crossed at 20 %
  // of the path, the cap plane (-0.1) at 67 %: in through the cap.
  ASSERT_TRUE(cylinder.sampleMoved(world(0.092, 0.0, -0.095), world(0.102, 0.0, -0.11), 0.01, s));
  EXPECT_LT((s.normal + axis).norm(), 1e-12);
  EXPECT_NEAR(s.distance, -0.005, 1e-12);
  // The side crossed last: the cap plane at 29 %, the side at 47 % (radially along -y here).
  ASSERT_TRUE(
      cylinder.sampleMoved(world(0.0, -0.092, -0.095), world(0.0, -0.107, -0.102), 0.01, s));
  EXPECT_LT((s.normal + radialY).norm(), 1e-12) << s.normal.transpose();
  EXPECT_NEAR(s.distance, -0.008, 1e-12);
  // A path that ends on the axis: the normal where it crossed the side.
  ASSERT_TRUE(cylinder.sampleMoved(world(0.0, 0.0, 0.0), world(0.0, 0.2, 0.0), 0.2, s));
  EXPECT_LT((s.normal - radialY).norm(), 1e-12) << s.normal.transpose();
  EXPECT_NEAR(s.distance, -0.1, 1e-12);
}

TEST_F(CylinderEntrySurface, OutsideOrAlreadyInsideIsTheSignedDistanceSample) {
  expectSampleMovedIsSampleOtherwise(
      cylinder,
      [&](const Vec3& q) {
        const Vec3 o = q - kCentre;
        const double a = o.dot(axis);
        return std::abs(a) <= 0.1 && (o - a * axis).norm() <= 0.1;
      },
      [&](std::mt19937& rng, Vec3& p, Vec3& from) {
        std::uniform_real_distribution<double> u(-0.2, 0.2);
        p = world(u(rng), u(rng), u(rng));
        from = world(0.6 * u(rng), 0.6 * u(rng), 0.6 * u(rng));
      },
      11);
}

}  // namespace
}  // namespace weft
