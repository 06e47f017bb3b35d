#pragma once
// The viewport's off-screen target: a framebuffer object (RGBA colour texture + depth) inside
// the editor's GL context, exposed as a RenderContext so the existing Renderer draws into it
// unchanged. ImGui then shows the colour texture as an image in the Viewport panel, and a
// viewport screenshot is the Renderer's own readPixels of this target.

#include <weft/render/RenderContext.h>

namespace weft::editor {

class ViewportTarget final : public render::RenderContext {
 public:
  // `parent` is the editor's context (window or OSMesa); it must outlive this target.
  ViewportTarget(render::RenderContext& parent, int width, int height);
  ~ViewportTarget() override;

  void* getProcAddress(const char* name) override { return parent_.getProcAddress(name); }
  unsigned framebuffer() const override { return framebuffer_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void resize(int width, int height) override;  // reallocates when the size changes
  std::string backendName() const override { return parent_.backendName() + "+fbo"; }

  unsigned colorTexture() const { return color_; }
  render::RenderContext& parent() const { return parent_; }

 protected:
  void bind() override { parent_.makeCurrent(); }
  void release() override {}  // the parent context stays current

 private:
  void allocate();
  void destroy();
  render::RenderContext& parent_;
  unsigned framebuffer_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace weft::editor
