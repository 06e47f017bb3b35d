// Tessellated obstacles lie on their analytic surfaces, with outward normals and outward
// (counter-clockwise) winding, since two-sided lighting tells front from back by winding.

#include <weft/render/ShapeTessellation.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

using render::LitMesh;
using render::Vec3f;

// Every triangle's winding normal points the way its vertex normals do.
void expectOutwardWinding(const LitMesh& m) {
  ASSERT_EQ(m.positions.size(), m.normals.size());
  ASSERT_EQ(m.indices.size() % 3, 0u);
  int checked = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const Vec3f a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                c = m.positions[m.indices[t + 2]];
    const Vec3f n = (b - a).cross(c - a);
    if (n.norm() < 1e-9f) continue;  // degenerate at a pole
    const Vec3f average =
        m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]];
    EXPECT_GT(n.dot(average), 0.0f) << "triangle " << t / 3;
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(ShapeTessellation, SphereLiesOnItsSurface) {
  const Vec3f center(0.5f, -1.0f, 2.0f);
  const LitMesh m = render::tessellateSphere(center, 0.7f);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR((m.positions[i] - center).norm(), 0.7f, 1e-5f);
    EXPECT_NEAR(m.normals[i].dot((m.positions[i] - center).normalized()), 1.0f, 1e-4f);
  }
  expectOutwardWinding(m);
}

TEST(ShapeTessellation, CapsuleIsWithinRadiusOfItsAxis) {
  const Vec3f a(0, 0, 0), b(1, 1, 0);
  const LitMesh m = render::tessellateCapsule(a, b, 0.2f);
  for (const Vec3f& p : m.positions) {
    const float t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0f, 1.0f);
    EXPECT_NEAR((p - (a + t * (b - a))).norm(), 0.2f, 1e-5f);
  }
  expectOutwardWinding(m);
}

TEST(ShapeTessellation, CylinderAndBoxAndPlaneWindOutward) {
  expectOutwardWinding(render::tessellateCylinder(Vec3f(0, 0, 0), Vec3f(0, 0, 1), 0.3f));
  const Eigen::Matrix3f rotation =
      Eigen::AngleAxisf(0.7f, Vec3f(1, 2, 3).normalized()).toRotationMatrix();
  const LitMesh box = render::tessellateBox(Vec3f(1, 2, 3), Vec3f(0.1f, 0.2f, 0.3f), rotation);
  EXPECT_EQ(box.triangleCount(), 12u);
  expectOutwardWinding(box);
  const LitMesh plane =
      render::tessellatePlane(Vec3f(0, -1, 0), Vec3f(0, 1, 0), Vec3f(3, 5, 0), 2.0f);
  expectOutwardWinding(plane);
  for (const Vec3f& p : plane.positions)
    EXPECT_FLOAT_EQ(p.y(), -1.0f);  // on the plane, around (3, -1, 0)
}

TEST(ShapeTessellation, ArrowReachesItsTip) {
  LitMesh m;
  render::appendArrow(m, Vec3f(1, 0, 0), Vec3f(0, 2, 0), 0.01f);
  float top = -1.0f;
  for (const Vec3f& p : m.positions) top = std::max(top, p.y());
  EXPECT_NEAR(top, 2.0f, 1e-5f);
  expectOutwardWinding(m);
  LitMesh none;
  render::appendArrow(none, Vec3f(0, 0, 0), Vec3f(0, 0, 0), 0.01f);
  EXPECT_TRUE(none.positions.empty());
}

}  // namespace
}  // namespace weft::test
