// The orbit camera's conventions and auto-framing.

#include <weft/render/Camera.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

using render::Vec3f;

Eigen::Vector3f project(const render::Camera& c, float aspect, const Vec3f& p) {
  const Eigen::Vector4f clip =
      c.projection(aspect) * c.view() * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
  return clip.head<3>() / clip.w();
}

TEST(Camera, NamedViewsLookAlongTheirAxes) {
  render::Bounds b;
  b.extend(Vec3f(-1, -1, -1));
  b.extend(Vec3f(1, 1, 1));
  const render::Camera front = render::namedViewCamera(render::NamedView::Front, b, 1.0f);
  EXPECT_NEAR((front.eye() - front.target).normalized().dot(Vec3f::UnitZ()), 1.0f, 1e-6f);
  EXPECT_NEAR(front.up().dot(Vec3f::UnitY()), 1.0f, 1e-6f);
  EXPECT_NEAR(front.right().dot(Vec3f::UnitX()), 1.0f, 1e-6f);
  const render::Camera side = render::namedViewCamera(render::NamedView::Side, b, 1.0f);
  EXPECT_NEAR((side.eye() - side.target).normalized().dot(Vec3f::UnitX()), 1.0f, 1e-6f);
  const render::Camera top = render::namedViewCamera(render::NamedView::Top, b, 1.0f);
  EXPECT_NEAR((top.eye() - top.target).normalized().dot(Vec3f::UnitY()), 1.0f, 1e-6f);
  EXPECT_NEAR(top.up().dot(-Vec3f::UnitZ()), 1.0f, 1e-6f);  // -Z is up in the top view
  EXPECT_NEAR(top.right().dot(Vec3f::UnitX()), 1.0f, 1e-6f);
}

TEST(Camera, AutoFramingShowsEveryCornerAndFillsTheView) {
  render::Bounds b;
  b.extend(Vec3f(-0.3f, 0.5f, -2.0f));
  b.extend(Vec3f(1.7f, 1.1f, 0.4f));
  for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f})
    for (render::NamedView v : {render::NamedView::Front, render::NamedView::Side,
                                render::NamedView::Top, render::NamedView::Auto})
      for (bool ortho : {false, true}) {
        render::Camera c = render::namedViewCamera(v, b, aspect);
        c.orthographic = ortho;
        float reach = 0.0f;
        for (int k = 0; k < 8; ++k) {
          const Vec3f p((k & 1) ? b.max.x() : b.min.x(), (k & 2) ? b.max.y() : b.min.y(),
                        (k & 4) ? b.max.z() : b.min.z());
          const Eigen::Vector3f ndc = project(c, aspect, p);
          EXPECT_LE(std::abs(ndc.x()), 1.0f) << "corner " << k;
          EXPECT_LE(std::abs(ndc.y()), 1.0f) << "corner " << k;
          EXPECT_GT(ndc.z(), -1.0f);
          EXPECT_LT(ndc.z(), 1.0f);
          reach = std::max({reach, std::abs(ndc.x()), std::abs(ndc.y())});
        }
        EXPECT_GT(reach, 0.8f) << "the scene should fill most of the view";
      }
}

TEST(Camera, OrbitKeepsTheTargetAndClampsPitch) {
  render::Camera c;
  c.target = Vec3f(1, 2, 3);
  c.orbit(30.0f, 200.0f);
  EXPECT_FLOAT_EQ(c.pitchDeg, 89.0f);
  EXPECT_NEAR((c.eye() - c.target).norm(), c.distance, 1e-5f);
  const Eigen::Vector3f center = project(c, 1.0f, c.target);
  EXPECT_NEAR(center.x(), 0.0f, 1e-5f);
  EXPECT_NEAR(center.y(), 0.0f, 1e-5f);
}

TEST(Camera, ParsesNamedViews) {
  render::NamedView v;
  EXPECT_TRUE(render::parseNamedView("top", v));
  EXPECT_EQ(v, render::NamedView::Top);
  EXPECT_FALSE(render::parseNamedView("diagonal", v));
}

}  // namespace
}  // namespace weft::test
