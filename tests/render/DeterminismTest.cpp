// Rendering is reproducible: the same frame gives the same bytes, again and from a new renderer.

#include "RenderTestSupport.h"

#include <weft/render/HeadlessContext.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

render::RenderScene busyScene() {
  DrapedSphere d = drapedSphere(24);
  d.scene.contacts = syntheticContacts(d, true);
  return d.scene;
}

TEST(Determinism, SameFrameTwiceGivesIdenticalBytes) {
  const render::RenderScene s = busyScene();
  render::RenderStyle style;
  style.wireframe = true;
  render::Renderer& r = osmesaRenderer(240, 180);
  const render::Image first = r.renderImage(s, goldenCamera(), style);
  r.renderImage(drapedSphere(8).scene, goldenCamera());  // something else in between
  const render::Image second = r.renderImage(s, goldenCamera(), style);
  ASSERT_EQ(first.pixels.size(), second.pixels.size());
  EXPECT_TRUE(first.pixels == second.pixels);
}

TEST(Determinism, AFreshRendererGivesIdenticalBytes) {
  const render::RenderScene s = busyScene();
  const render::Image shared = osmesaRenderer(240, 180).renderImage(s, goldenCamera());
  auto context = render::createHeadlessContext(240, 180, render::HeadlessBackend::OsMesa);
  render::Renderer fresh(*context);
  const render::Image own = fresh.renderImage(s, goldenCamera());
  EXPECT_TRUE(shared.pixels == own.pixels);
}

}  // namespace
}  // namespace weft::test
