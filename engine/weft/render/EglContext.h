#pragma once
// Off-screen rendering through EGL's Mesa surfaceless platform (EGL_PLATFORM_SURFACELESS_MESA):
// a 3.3 core context with no surface at all, drawing into a framebuffer object this backend
// owns. Used where OSMesa is missing (upstream Mesa has dropped it).

#include <weft/render/RenderContext.h>

#include <memory>

namespace weft::render {

class EglContext final : public RenderContext {
 public:
  // Throws ContextError when libEGL, the surfaceless platform or a 3.3 core context is missing.
  EglContext(int width, int height);
  ~EglContext() override;

  void* getProcAddress(const char* name) override;
  unsigned framebuffer() const override { return framebuffer_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void resize(int width, int height) override;
  std::string backendName() const override { return "egl"; }

 protected:
  void bind() override;
  void release() override;

 private:
  void create(int width, int height);
  void destroy();
  void releaseFramebuffer();
  struct Library;
  struct Gl;
  std::unique_ptr<Library> lib_;
  std::unique_ptr<Gl> gl_;
  void* display_ = nullptr;
  void* context_ = nullptr;
  unsigned framebuffer_ = 0, colorBuffer_ = 0, depthBuffer_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace weft::render
