// Pixel-level checks that cannot pass by accident: with an orthographic camera the mapping from
// scene to pixels is known exactly, so each test states which pixels must show what.

#include "RenderTestSupport.h"

#include <weft/render/ColorMap.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace weft::test {
namespace {

// Looking along -Z at the origin; the image spans y in [-1, 1] and x in [-aspect, aspect].
render::Camera orthoFront() {
  render::Camera c;
  c.orthographic = true;
  c.orthoHalfHeight = 1.0f;
  c.distance = 5.0f;
  c.nearPlane = 0.1f;
  c.farPlane = 10.0f;
  return c;
}

// Scene point of a pixel centre for orthoFront() in a width x height image.
Eigen::Vector2f pixelCenter(int x, int y, int width, int height) {
  const float unitsPerPixel = 2.0f / float(height);
  return {-float(width) / float(height) + (float(x) + 0.5f) * unitsPerPixel,
          1.0f - (float(y) + 0.5f) * unitsPerPixel};
}

// Signed distance (positive inside) from a point to a counter-clockwise triangle.
float insideDistance(const Eigen::Vector2f& p, const std::array<Eigen::Vector2f, 3>& t) {
  float d = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2f a = t[k], b = t[(k + 1) % 3], e = (b - a).normalized();
    d = std::min(d, e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x()));
  }
  return d;
}

render::RenderStyle plainStyle() {
  render::RenderStyle style;
  style.groundGrid = false;
  style.legend = false;
  return style;
}

void checkTriangle(bool frontFacing) {
  const int w = 200, h = 100;
  const std::array<Eigen::Vector2f, 3> tri = {
      Eigen::Vector2f(-1.0f, -0.5f), Eigen::Vector2f(1.0f, -0.5f), Eigen::Vector2f(0.0f, 0.5f)};
  render::RenderScene s;
  s.cloth.positions.resize(3, 3);
  for (int k = 0; k < 3; ++k) s.cloth.positions.row(k) << tri[k].x(), tri[k].y(), 0.0f;
  s.cloth.triangles.resize(1, 3);
  if (frontFacing)
    s.cloth.triangles << 0, 1, 2;
  else
    s.cloth.triangles << 0, 2, 1;
  const render::RenderStyle style = plainStyle();
  const render::Image image = osmesaRenderer(w, h).renderImage(s, orthoFront(), style);
  const auto background = bytesOf(style.background);
  const float pixel = 2.0f / float(h), margin = 1.5f * pixel;
  int inside = 0, outside = 0;
  const std::uint8_t* first = nullptr;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float d = insideDistance(pixelCenter(x, y, w, h), tri);
      const std::uint8_t* p = image.at(x, y);
      if (d > margin) {
        ++inside;
        ASSERT_FALSE(pixelIs(image, x, y, background))
            << "pixel " << x << "," << y << " inside the triangle";
        // A flat triangle under directional light, seen orthographically: one colour throughout.
        if (!first) first = p;
        ASSERT_TRUE(p[0] == first[0] && p[1] == first[1] && p[2] == first[2])
            << "pixel " << x << "," << y;
      } else if (d < -margin) {
        ++outside;
        ASSERT_TRUE(pixelIs(image, x, y, background))
            << "pixel " << x << "," << y << " outside the triangle";
      }
    }
  // The triangle spans 100 x 50 pixels: about 2500 inside, minus the margin band.
  EXPECT_GT(inside, 2000);
  EXPECT_GT(outside, 17000);
  ASSERT_NE(first, nullptr);
  if (frontFacing)
    EXPECT_GT(int(first[0]), int(first[2]) + 60) << "front colour is orange";
  else
    EXPECT_GT(int(first[2]), int(first[0]) + 60) << "back colour is blue";
}

TEST(Pixels, KnownFrontFacingTriangleLandsOnKnownPixels) {
  checkTriangle(true);
}

TEST(Pixels, BackFacingTriangleIsLitWithTheBackColour) {
  checkTriangle(false);
}

TEST(Pixels, EmptySceneIsBackgroundEverywhere) {
  render::RenderStyle style = plainStyle();
  style.background = {0.2f, 0.4f, 0.6f};
  const render::Image image =
      osmesaRenderer(64, 48).renderImage(render::RenderScene{}, orthoFront(), style);
  const auto background = bytesOf(style.background);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      ASSERT_TRUE(pixelIs(image, x, y, background)) << x << "," << y;
}

TEST(Pixels, ImageRowsRunFromTopToBottom) {
  // A triangle in the upper half of the view must land in the first rows of the image.
  render::RenderScene s;
  s.cloth.positions.resize(3, 3);
  s.cloth.positions << -0.5f, 0.2f, 0.0f, 0.5f, 0.2f, 0.0f, 0.0f, 0.9f, 0.0f;
  s.cloth.triangles.resize(1, 3);
  s.cloth.triangles << 0, 1, 2;
  const render::RenderStyle style = plainStyle();
  const render::Image image = osmesaRenderer(100, 100).renderImage(s, orthoFront(), style);
  const auto background = bytesOf(style.background);
  EXPECT_FALSE(pixelIs(image, 50, 30, background));  // y = 0.39: inside
  EXPECT_TRUE(pixelIs(image, 50, 70, background));   // y = -0.41: below it
}

// The see-through views (RenderStyle::clothOpacity, obstaclesInFront) on a cloth square in front
// of a sphere: opaque, the middle pixel is the cloth's own; translucent cloth, or obstacles drawn
// in front, give a pixel between the cloth's and the sphere's colours, far from either.
TEST(Pixels, SeeThroughClothAndObstaclesInFrontShowTheObstacleBehind) {
  const int size = 100;
  render::RenderScene cloth, sphere, both;
  cloth.cloth = flatSquare(4, 1.6f);  // in z = 0, facing the camera
  render::ObstacleShape ball;
  ball.kind = render::ObstacleShape::Kind::Sphere;
  ball.center = render::Vec3f(0.0f, 0.0f, -0.8f);  // behind the cloth
  ball.radius = 0.5f;
  sphere.obstacles = {ball};
  both.cloth = cloth.cloth;
  both.obstacles = {ball};
  const render::RenderStyle plain = plainStyle();
  auto middle = [&](const render::RenderScene& scene, const render::RenderStyle& style) {
    const render::Image image = osmesaRenderer(size, size).renderImage(scene, orthoFront(), style);
    const std::uint8_t* p = image.at(size / 2, size / 2);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const auto clothOnly = middle(cloth, plain), sphereOnly = middle(sphere, plain);
  ASSERT_GT(std::abs(clothOnly[2] - sphereOnly[2]), 60) << "the two colours differ";
  EXPECT_EQ(middle(both, plain), clothOnly) << "opaque cloth hides the sphere";
  render::RenderStyle seeThrough = plain;
  seeThrough.clothOpacity = 0.4f;
  render::RenderStyle inFront = plain;
  inFront.obstaclesInFront = true;
  for (const auto& [name, style] :
       {std::pair<const char*, render::RenderStyle>{"see-through", seeThrough},
        {"in front", inFront}}) {
    SCOPED_TRACE(name);
    const auto mixed = middle(both, style);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(mixed[c], std::min(clothOnly[c], sphereOnly[c]) - 2) << c;
      EXPECT_LE(mixed[c], std::max(clothOnly[c], sphereOnly[c]) + 2) << c;
    }
    // Blue differs most between the two: the mix lies well inside, at neither end.
    EXPECT_GT(std::abs(mixed[2] - clothOnly[2]), 20);
    EXPECT_GT(std::abs(mixed[2] - sphereOnly[2]), 20);
  }
}

// Two pin groups' markers: the first in the style's near-black, the second in its own colour
// (brown: red well above blue); without groups both take the style's colour.
TEST(Pixels, PinGroupMarkersTakeTheirGroupsColour) {
  const int size = 100;
  render::RenderScene s;
  s.fixedPoints = {render::Vec3f(-0.5f, 0.0f, 0.0f), render::Vec3f(0.5f, 0.0f, 0.0f)};
  render::RenderStyle style = plainStyle();
  style.pointSize = 16.0f;
  const auto centre = [&](const render::Image& image, int k) {
    const int x = k == 0 ? size / 4 : 3 * size / 4;
    const std::uint8_t* p = image.at(x, size / 2);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const render::Image plain = osmesaRenderer(size, size).renderImage(s, orthoFront(), style);
  s.fixedPointGroups = {0, 1};
  const render::Image grouped = osmesaRenderer(size, size).renderImage(s, orthoFront(), style);
  for (const render::Image* image : {&plain, &grouped}) {
    const auto first = centre(*image, 0);
    EXPECT_LT(std::max({first[0], first[1], first[2]}), 90) << "group 0: near-black";
  }
  const auto second = centre(plain, 1), brown = centre(grouped, 1);
  EXPECT_LT(std::max({second[0], second[1], second[2]}), 90) << "no groups: the style's colour";
  EXPECT_GT(brown[0], brown[2] + 50) << "group 1: brown";
  EXPECT_GT(brown[0], 90);
}

TEST(Pixels, BranchColourAppearsOnlyWhereThatBranchHasNodes) {
  const int size = 200;
  render::RenderScene s;
  s.cloth = flatSquare(10, 1.6f);  // 11 x 11 nodes 0.16 apart, 16 pixels apart on screen
  render::ContactOverlay contacts;
  for (Eigen::Index i = 0; i < s.cloth.positions.rows(); ++i) {
    const int column = int(i % 11);
    contacts.branches.push_back(column < 3   ? render::ContactBranch::Stick
                                : column > 7 ? render::ContactBranch::Slip
                                             : render::ContactBranch::None);
  }
  s.contacts = contacts;
  render::RenderStyle style = plainStyle();
  style.pointSize = 10.0f;  // contact discs are 0.6 of it: 6 pixels across
  const render::Image image = osmesaRenderer(size, size).renderImage(s, orthoFront(), style);

  auto screen = [&](Eigen::Index node) {
    return Eigen::Vector2f((s.cloth.positions(node, 0) + 1.0f) * size / 2.0f,
                           (1.0f - s.cloth.positions(node, 1)) * size / 2.0f);
  };
  for (render::ContactBranch branch : {render::ContactBranch::TakeOff, render::ContactBranch::Stick,
                                       render::ContactBranch::Slip}) {
    const auto colour = bytesOf(render::branchColor(branch));
    int coloured = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (!pixelIs(image, x, y, colour)) continue;
        ++coloured;
        float nearest = INFINITY;
        for (Eigen::Index i = 0; i < s.cloth.positions.rows(); ++i)
          if (contacts.branches[std::size_t(i)] == branch)
            nearest = std::min(nearest, (screen(i) - Eigen::Vector2f(x + 0.5f, y + 0.5f)).norm());
        ASSERT_LE(nearest, 3.0f + 1.0f)
            << "branch colour at pixel " << x << "," << y << " far from its nodes";
      }
    int nodes = 0;
    for (Eigen::Index i = 0; i < s.cloth.positions.rows(); ++i) {
      if (contacts.branches[std::size_t(i)] != branch) continue;
      ++nodes;
      const Eigen::Vector2f c = screen(i);  // the square spans pixels 20 to 180: no disc is cut
      EXPECT_TRUE(pixelIs(image, int(c.x()), int(c.y()), colour)) << "node " << i;
    }
    if (branch == render::ContactBranch::TakeOff)
      EXPECT_EQ(coloured, 0) << "take-off has no nodes";
    else
      EXPECT_GT(coloured, nodes * 20);  // a 6-pixel disc covers about 28 pixels
  }
}

}  // namespace
}  // namespace weft::test
