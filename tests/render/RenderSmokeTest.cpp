// Every draw path, headless, with GL errors checked after each path (a GL error throws and
// fails the test): each obstacle kind, each overlay and colour map, markers, curves, arrows,
// ghosts, wireframe, legends, every named view, perspective and orthographic.

#include "RenderTestSupport.h"

#include <weft/render/ColorMap.h>
#include <weft/render/EglContext.h>
#include <weft/render/RenderError.h>

#include <gtest/gtest.h>

#include <stdexcept>

namespace weft::test {
namespace {

render::RenderScene everything() {
  DrapedSphere d = drapedSphere(12);
  render::RenderScene s = d.scene;
  using K = render::ObstacleShape::Kind;
  render::ObstacleShape capsule;
  capsule.kind = K::Capsule;
  capsule.a = {1.0f, -0.6f, 0.0f}, capsule.b = {1.0f, 0.2f, 0.3f}, capsule.radius = 0.15f;
  render::ObstacleShape box;
  box.kind = K::Box;
  box.center = {-1.0f, -0.6f, 0.0f}, box.halfExtents = {0.2f, 0.3f, 0.1f};
  box.rotation = Eigen::AngleAxisf(0.4f, render::Vec3f::UnitY()).toRotationMatrix();
  render::ObstacleShape cylinder;
  cylinder.kind = K::Cylinder;
  cylinder.a = {0.0f, -0.9f, 1.0f}, cylinder.b = {0.0f, -0.3f, 1.0f}, cylinder.radius = 0.1f;
  render::ObstacleShape mesh;
  mesh.kind = K::Mesh;
  mesh.mesh = flatSquare(2, 0.4f);
  mesh.mesh.positions.rowwise() += render::Vec3f(0.0f, 0.0f, -1.0f).transpose();
  mesh.smoothNormals = false;
  render::ObstacleShape smoothMesh = mesh;
  smoothMesh.smoothNormals = true;
  smoothMesh.mesh.positions.rowwise() += render::Vec3f(0.5f, 0.0f, 0.0f).transpose();
  s.obstacles.insert(s.obstacles.end(), {capsule, box, cylinder, mesh, smoothMesh});
  s.contacts = syntheticContacts(d, true);
  s.fixedPoints = {s.cloth.positions.row(0).transpose()};
  s.handlePoints = {s.cloth.positions.row(12).transpose()};
  s.targetPoints = {render::Vec3f(0.0f, 0.8f, 0.0f)};
  s.curves.push_back(
      {{{0.8f, 0.6f, 0.8f}, {0.9f, 0.8f, 0.6f}, {1.0f, 0.9f, 0.2f}}, {0.1f, 0.6f, 0.3f}});
  render::GhostMesh ghost;
  ghost.mesh = s.cloth;
  ghost.mesh.positions.rowwise() += render::Vec3f(0.0f, 0.1f, 0.0f).transpose();
  s.ghosts.push_back(ghost);
  return s;
}

std::size_t nonBackgroundPixels(const render::Image& image, const render::RenderStyle& style) {
  const auto bg = bytesOf(style.background);
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += pixelIs(image, x, y, bg) ? 0 : 1;
  return n;
}

TEST(RenderSmoke, EveryDrawPathWithoutGlErrors) {
  render::Renderer& r = osmesaRenderer(200, 150);
  const render::RenderScene base = everything();
  for (bool wireframe : {false, true})
    for (int coloring = 0; coloring < 3; ++coloring) {
      render::RenderScene s = base;
      if (coloring > 0) {
        render::ScalarColoring c;
        for (Eigen::Index i = 0; i < s.cloth.positions.rows(); ++i)
          c.values.push_back(s.cloth.positions(i, 1));
        c.low = -0.5f, c.high = 0.5f;
        c.map = coloring == 1 ? render::ColorMapKind::Sequential : render::ColorMapKind::Diverging;
        s.scalars = c;
      }
      render::RenderStyle style;
      style.wireframe = wireframe;
      const render::Image image = r.renderImage(
          s,
          render::namedViewCamera(render::NamedView::Auto, render::sceneBounds(s), 200.0f / 150.0f),
          style);
      EXPECT_GT(nonBackgroundPixels(image, style), 200u * 150u / 4)
          << "wireframe " << wireframe << " coloring " << coloring;
    }
}

TEST(RenderSmoke, EveryNamedViewAndProjection) {
  render::Renderer& r = osmesaRenderer(160, 120);
  const render::RenderScene s = everything();
  for (render::NamedView v : {render::NamedView::Front, render::NamedView::Side,
                              render::NamedView::Top, render::NamedView::Auto})
    for (bool ortho : {false, true}) {
      render::Camera framed = render::namedViewCamera(v, render::sceneBounds(s), 160.0f / 120.0f);
      framed.orthographic = ortho;
      EXPECT_GT(nonBackgroundPixels(r.renderImage(s, framed), {}), 160u * 120u / 10);
    }
}

TEST(RenderSmoke, EmptySceneAndEmptyPiecesDrawNothingAndRaiseNothing) {
  render::Renderer& r = osmesaRenderer(64, 48);
  render::RenderScene s;
  s.curves.push_back({});                 // a curve without points
  s.ghosts.push_back({});                 // a ghost without triangles
  s.contacts = render::ContactOverlay{};  // an overlay on no vertices
  render::RenderStyle style;
  style.legend = false;  // the contact legend would be the only thing drawn
  EXPECT_EQ(nonBackgroundPixels(r.renderImage(s, render::Camera{}, style), style), 0u);
}

TEST(RenderSmoke, InconsistentScenesAreRejectedBeforeDrawing) {
  render::Renderer& r = osmesaRenderer(64, 48);
  render::RenderScene s = drapedSphere(4).scene;
  s.scalars = render::ScalarColoring{{1.0f, 2.0f}, 0.0f, 1.0f, render::ColorMapKind::Sequential};
  EXPECT_THROW(r.render(s, render::Camera{}), std::invalid_argument);
  s.scalars.reset();
  s.cloth.triangles(0, 0) = 1000;
  EXPECT_THROW(r.render(s, render::Camera{}), std::invalid_argument);
}

TEST(RenderSmoke, EglSurfacelessBackendDrawsTheSameScene) {
  std::unique_ptr<render::EglContext> egl;
  try {
    egl = std::make_unique<render::EglContext>(160, 120);
  } catch (const render::ContextError& e) {
    GTEST_SKIP() << "no EGL surfaceless here: " << e.what();
  }
  render::RendererOptions options;
  options.checkEveryDrawPath = true;
  render::Renderer r(*egl, options);
  const render::RenderScene s = everything();
  const render::Camera c =
      render::namedViewCamera(render::NamedView::Auto, render::sceneBounds(s), 160.0f / 120.0f);
  const render::Image image = r.renderImage(s, c);
  EXPECT_GT(nonBackgroundPixels(image, {}), 160u * 120u / 4);
  // Both backends are Mesa's llvmpipe here, drawing the same commands.
  osmesaRenderer(160, 120);  // the shared OSMesa context, re-made current by render()
  const render::Image reference = osmesaRenderer(160, 120).renderImage(s, c);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    differing += image.pixels[i] != reference.pixels[i];
  EXPECT_LT(differing, image.pixels.size() / 100);
}

}  // namespace
}  // namespace weft::test
