#pragma once
// An on-screen context: a GLFW window with an OpenGL 3.3 core profile, drawing into the
// window's default framebuffer. Lives in its own target (weft_render_glfw) so that headless
// tools do not link the windowing system.

#include <weft/render/RenderContext.h>

#include <string>

struct GLFWwindow;

namespace weft::render {

class GlfwContext final : public RenderContext {
 public:
  // Throws ContextError when there is no display or no 3.3 core context.
  GlfwContext(const std::string& title, int width, int height, bool visible = true);
  ~GlfwContext() override;

  void* getProcAddress(const char* name) override;
  unsigned framebuffer() const override { return 0; }
  int width() const override;  // framebuffer pixels (may differ from window units on HiDPI)
  int height() const override;
  void resize(int width, int height) override;
  void present() override;
  std::string backendName() const override { return "glfw"; }

  GLFWwindow* window() const { return window_; }

 protected:
  void bind() override;
  void release() override;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace weft::render
