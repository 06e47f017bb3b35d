// The scene contract's transform: rotate about X, then Y, then Z (degrees), then translate.

#include <support/SceneBuilder.h>
#include <weft/mesh/GridMesh.h>
#include <weft/mesh/RigidTransform.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

// Elementary rotations written out, independently of the implementation's Eigen::AngleAxis.
Mat3 rotX(double deg) {
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  Mat3 r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}
Mat3 rotY(double deg) {
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  Mat3 r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}
Mat3 rotZ(double deg) {
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  Mat3 r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

TEST(RigidTransform, SingleAxisRotationsFollowTheRightHandRule) {
  RigidTransform t;
  t.rotateDeg = Vec3(90, 0, 0);
  EXPECT_TRUE(t.apply(Vec3::UnitY()).isApprox(Vec3::UnitZ(), 1e-15));
  t.rotateDeg = Vec3(0, 90, 0);
  EXPECT_TRUE(t.apply(Vec3::UnitZ()).isApprox(Vec3::UnitX(), 1e-15));
  t.rotateDeg = Vec3(0, 0, 90);
  EXPECT_TRUE(t.apply(Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-15));
}

TEST(RigidTransform, RotatesAboutXThenYThenZ) {
  // (0, 1, 0): X by 90 gives (0, 0, 1); Y by 90 then gives (1, 0, 0). The reverse order
  // (Y first) would leave it at (0, 0, 1).
  RigidTransform t;
  t.rotateDeg = Vec3(90, 90, 0);
  const Vec3 p = t.apply(Vec3::UnitY());
  EXPECT_NEAR((p - Vec3::UnitX()).norm(), 0.0, 1e-15) << p.transpose();

  t.rotateDeg = Vec3(30, -50, 70);
  const Mat3 expected = rotZ(70) * rotY(-50) * rotX(30);
  EXPECT_NEAR((t.rotation() - expected).norm(), 0.0, 1e-14);
  EXPECT_GT((t.rotation() - rotX(30) * rotY(-50) * rotZ(70)).norm(), 0.1)
      << "the test angles must distinguish the orders";
  EXPECT_NEAR((t.rotation().transpose() * t.rotation() - Mat3::Identity()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(t.rotation().determinant(), 1.0, 1e-14);
}

TEST(RigidTransform, TranslatesAfterRotating) {
  RigidTransform t;
  t.rotateDeg = Vec3(0, 0, 90);
  t.translate = Vec3(1, 2, 3);
  EXPECT_TRUE(t.apply(Vec3::Zero()).isApprox(t.translate));
  // R p + t = (0,1,0) + (1,2,3); translating first would give R (p + t) = (-2, 2, 3).
  EXPECT_NEAR((t.apply(Vec3::UnitX()) - Vec3(1, 3, 3)).norm(), 0.0, 1e-15);
}

TEST(RigidTransform, ApplyToMatchesApplyRowByRow) {
  RigidTransform t;
  t.rotateDeg = Vec3(12, 34, 56);
  t.translate = Vec3(-0.5, 0.25, 2.0);
  NodeMatrix points = makeGrid(1.0, 2.0, 3, 2).vertices;
  const NodeMatrix original = points;
  t.applyTo(points);
  for (int i = 0; i < points.rows(); ++i) {
    const Vec3 expected =
        rotZ(56) * rotY(34) * rotX(12) * original.row(i).transpose() + t.translate;
    EXPECT_NEAR((points.row(i).transpose() - expected).norm(), 0.0, 1e-14) << "vertex " << i;
  }
}

TEST(RigidTransform, SceneTransformRotatesTheGridNormal) {
  // A grid rotated 90 degrees about X faces +Z (its normal +Y maps to +Z), then moves up.
  nlohmann::json doc = test::gridScene(1.0, 2, 0.01, 1);
  doc["cloths"][0]["mesh"]["transform"] = {{"rotate_deg", {90, 0, 0}}, {"translate", {0, 1, 0}}};
  const Scene scene = test::parse(doc);
  const TriangleMesh& mesh = scene.cloths[0].mesh;
  const TriangleMesh flat = makeGrid(1.0, 1.0, 2, 2);
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    const Vec3 f = flat.vertices.row(i);
    // Rx(90) maps (x, 0, z) to (x, -z, 0).
    EXPECT_NEAR((mesh.vertices.row(i).transpose() - Vec3(f.x(), 1.0 - f.z(), 0.0)).norm(), 0.0,
                1e-15);
  }
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 a = mesh.vertices.row(mesh.triangles(t, 0)),
               b = mesh.vertices.row(mesh.triangles(t, 1)),
               c = mesh.vertices.row(mesh.triangles(t, 2));
    EXPECT_GT((b - a).cross(c - a).normalized().z(), 1.0 - 1e-12);
  }
}

}  // namespace
}  // namespace weft
