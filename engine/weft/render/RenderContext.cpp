#include <weft/render/RenderContext.h>

namespace weft::render {

thread_local RenderContext* RenderContext::current_ = nullptr;

RenderContext::~RenderContext() {
  if (current_ == this) current_ = nullptr;  // a derived destructor has released it already
}

void RenderContext::makeCurrent() {
  if (current_ && current_ != this) {
    current_->release();
    current_ = nullptr;
  }
  // Always bound again: an off-screen buffer may have been reallocated since.
  bind();
  current_ = this;
}

void RenderContext::releaseIfCurrent() {
  if (current_ == this) {
    release();
    current_ = nullptr;
  }
}

}  // namespace weft::render
