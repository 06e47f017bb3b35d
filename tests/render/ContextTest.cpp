// The context backends behind one interface, and the GL function table loaded from them.

#include <weft/render/GlFunctions.h>
#include <weft/render/GlfwContext.h>
#include <weft/render/HeadlessContext.h>
#include <weft/render/RenderError.h>
#include <weft/render/Renderer.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

namespace weft::test {
namespace {

TEST(Context, OsMesaGivesACore33ContextAndLogsWhatDraws) {
  std::ostringstream log;
  auto context = render::createHeadlessContext(32, 16, render::HeadlessBackend::OsMesa, &log);
  EXPECT_EQ(context->backendName(), "osmesa");
  EXPECT_EQ(context->width(), 32);
  EXPECT_EQ(context->height(), 16);
  EXPECT_NE(log.str().find("GL_VERSION"), std::string::npos);
  EXPECT_NE(log.str().find("GL_RENDERER"), std::string::npos);
  render::GlFunctions gl;
  gl.load([&](const char* name) { return context->getProcAddress(name); });
  GLint major = 0, minor = 0, profile = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  gl.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 33);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_NO_THROW(gl.check("querying the version"));
}

TEST(Context, GlErrorsBecomeExceptionsNamingThePlace) {
  auto context = render::createHeadlessContext(8, 8, render::HeadlessBackend::OsMesa);
  render::GlFunctions gl;
  gl.load([&](const char* name) { return context->getProcAddress(name); });
  gl.Enable(0xFFFF);  // not a capability: GL_INVALID_ENUM
  try {
    gl.check("enabling nonsense");
    FAIL() << "no GlError";
  } catch (const render::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("enabling nonsense"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("GL_INVALID_ENUM"), std::string::npos);
  }
  EXPECT_NO_THROW(gl.check("after the queue was cleared"));
}

TEST(Context, ResizingChangesTheImageSize) {
  auto context = render::createHeadlessContext(40, 30, render::HeadlessBackend::Auto);
  render::Renderer renderer(*context);
  EXPECT_EQ(renderer.renderImage({}, render::Camera{}).width, 40);
  context->resize(24, 50);
  const render::Image image = renderer.renderImage({}, render::Camera{});
  EXPECT_EQ(image.width, 24);
  EXPECT_EQ(image.height, 50);
}

TEST(Context, EglSurfacelessRendersIntoItsOwnFramebuffer) {
  std::unique_ptr<render::RenderContext> egl;
  try {
    egl = render::createHeadlessContext(20, 10, render::HeadlessBackend::Egl);
  } catch (const render::ContextError& e) {
    GTEST_SKIP() << e.what();
  }
  EXPECT_EQ(egl->backendName(), "egl");
  EXPECT_NE(egl->framebuffer(), 0u);
  render::Renderer renderer(*egl);
  render::RenderStyle style;
  style.background = {1.0f, 0.0f, 0.0f};
  const render::Image image = renderer.renderImage({}, render::Camera{}, style);
  EXPECT_EQ(image.at(5, 5)[0], 255);
  EXPECT_EQ(image.at(5, 5)[1], 0);
}

TEST(Context, SwitchingBetweenOsMesaAndEglKeepsBothWorking) {
  // Both are Mesa and share its GL dispatch layer: a context switch that skips releasing the
  // other backend's context broke OSMesa after the EGL context went away.
  render::RenderScene triangle;
  triangle.cloth.positions.resize(3, 3);
  triangle.cloth.positions << -1, -1, 0, 1, -1, 0, 0, 1, 0;
  triangle.cloth.triangles.resize(1, 3);
  triangle.cloth.triangles << 0, 1, 2;
  render::RendererOptions strict;
  strict.checkEveryDrawPath = true;
  auto osmesa = render::createHeadlessContext(48, 32, render::HeadlessBackend::OsMesa);
  render::Renderer a(*osmesa, strict);
  const render::Image before = a.renderImage(triangle, render::Camera{});
  {
    std::unique_ptr<render::RenderContext> egl;
    try {
      egl = render::createHeadlessContext(48, 32, render::HeadlessBackend::Egl);
    } catch (const render::ContextError& e) {
      GTEST_SKIP() << e.what();
    }
    render::Renderer b(*egl, strict);
    EXPECT_TRUE(b.renderImage(triangle, render::Camera{}).pixels == before.pixels);
    EXPECT_TRUE(a.renderImage(triangle, render::Camera{}).pixels == before.pixels);
    EXPECT_TRUE(b.renderImage(triangle, render::Camera{}).pixels == before.pixels);
  }
  EXPECT_TRUE(a.renderImage(triangle, render::Camera{}).pixels == before.pixels);
}

TEST(Context, ParsesBackendNames) {
  render::HeadlessBackend b;
  EXPECT_TRUE(render::parseHeadlessBackend("egl", b));
  EXPECT_EQ(b, render::HeadlessBackend::Egl);
  EXPECT_FALSE(render::parseHeadlessBackend("vulkan", b));
}

TEST(Context, GlfwWindowNeedsADisplay) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland)) {
    render::GlfwContext window("weft test", 64, 48, false);
    render::Renderer renderer(window);
    EXPECT_GT(renderer.renderImage({}, render::Camera{}).width, 0);
  } else {
    // No display: a clear ContextError, not a crash.
    EXPECT_THROW(render::GlfwContext("weft test", 64, 48, false), render::ContextError);
  }
}

}  // namespace
}  // namespace weft::test
