#include "ViewportTarget.h"

#include "EditorGl.h"

#include <weft/render/RenderError.h>

#include <algorithm>
#include <string>

namespace weft::editor {

ViewportTarget::ViewportTarget(render::RenderContext& parent, int width, int height)
    : parent_(parent), width_(std::max(width, 1)), height_(std::max(height, 1)) {
  parent_.makeCurrent();
  allocate();
}

ViewportTarget::~ViewportTarget() {
  try {
    parent_.makeCurrent();
    destroy();
  } catch (...) {
  }
  releaseIfCurrent();
}

void ViewportTarget::resize(int width, int height) {
  width = std::max(width, 1);
  height = std::max(height, 1);
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  parent_.makeCurrent();
  destroy();
  allocate();
}

void ViewportTarget::allocate() {
  const WeftEditorGl& gl = weftEditorGl;
  gl.GenTextures(1, &color_);
  gl.BindTexture(GL_TEXTURE_2D, color_);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width_, height_, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.GenRenderbuffers(1, &depth_);
  gl.BindRenderbuffer(GL_RENDERBUFFER, depth_);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width_, height_);
  gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
  gl.GenFramebuffers(1, &framebuffer_);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl.BindFramebuffer(GL_FRAMEBUFFER, parent_.framebuffer());
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw render::ContextError("the viewport framebuffer is incomplete (status " +
                               std::to_string(status) + ")");
}

void ViewportTarget::destroy() {
  const WeftEditorGl& gl = weftEditorGl;
  if (framebuffer_) gl.DeleteFramebuffers(1, &framebuffer_);
  if (depth_) gl.DeleteRenderbuffers(1, &depth_);
  if (color_) gl.DeleteTextures(1, &color_);
  framebuffer_ = depth_ = color_ = 0;
}

}  // namespace weft::editor
