#pragma once
// Where the renderer draws: an OpenGL 3.3 core context and the framebuffer it renders into.
// Backends (a GLFW window, an OSMesa buffer, an EGL surfaceless FBO) implement this; nothing
// else in the renderer knows which one it runs on.

#include <string>

namespace weft::render {

class RenderContext {
 public:
  virtual ~RenderContext();
  RenderContext() = default;
  RenderContext(const RenderContext&) = delete;
  RenderContext& operator=(const RenderContext&) = delete;

  // Makes this context current on the calling thread. Another backend's context that is
  // current is released first: Mesa's OSMesa and its EGL driver share one GL dispatch layer,
  // and switching straight from one to the other corrupts the state of both.
  void makeCurrent();
  // Address of a GL function by its full name ("glClear"), from this context's implementation.
  virtual void* getProcAddress(const char* name) = 0;
  // The framebuffer the renderer draws into and reads back from (0: the default one).
  virtual unsigned framebuffer() const = 0;
  // Size of that framebuffer in pixels.
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Off-screen backends reallocate their buffers; a window resizes itself.
  virtual void resize(int width, int height) = 0;
  // Shows the frame (swaps a window's buffers); nothing for off-screen backends.
  virtual void present() {}
  virtual std::string backendName() const = 0;

 protected:
  virtual void bind() = 0;     // the backend's make-current call
  virtual void release() = 0;  // the backend's "no context current" call
  // Derived destructors call this first, while the backend can still release itself.
  void releaseIfCurrent();

 private:
  static thread_local RenderContext* current_;
};

}  // namespace weft::render
