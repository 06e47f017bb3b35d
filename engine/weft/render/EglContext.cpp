#include <weft/render/EglContext.h>

#include <weft/render/GlFunctions.h>
#include <weft/render/RenderError.h>
#include <weft/render/SharedLibrary.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>

namespace weft::render {

struct EglContext::Library {
  SharedLibrary so{libraryNames("WEFT_EGL_LIBRARY", {"libEGL.so.1", "libEGL.so"})};
  PFNEGLGETPROCADDRESSPROC getProcAddress =
      so.function<PFNEGLGETPROCADDRESSPROC>("eglGetProcAddress");
  PFNEGLQUERYSTRINGPROC queryString = so.function<PFNEGLQUERYSTRINGPROC>("eglQueryString");
  PFNEGLGETERRORPROC getError = so.function<PFNEGLGETERRORPROC>("eglGetError");
  PFNEGLINITIALIZEPROC initialize = so.function<PFNEGLINITIALIZEPROC>("eglInitialize");
  PFNEGLTERMINATEPROC terminate = so.function<PFNEGLTERMINATEPROC>("eglTerminate");
  PFNEGLBINDAPIPROC bindApi = so.function<PFNEGLBINDAPIPROC>("eglBindAPI");
  PFNEGLCHOOSECONFIGPROC chooseConfig = so.function<PFNEGLCHOOSECONFIGPROC>("eglChooseConfig");
  PFNEGLCREATECONTEXTPROC createContext = so.function<PFNEGLCREATECONTEXTPROC>("eglCreateContext");
  PFNEGLDESTROYCONTEXTPROC destroyContext =
      so.function<PFNEGLDESTROYCONTEXTPROC>("eglDestroyContext");
  PFNEGLMAKECURRENTPROC makeCurrent = so.function<PFNEGLMAKECURRENTPROC>("eglMakeCurrent");
  // Optional in the library itself: core only from EGL 1.5, otherwise an extension.
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(getProcAddress("eglGetPlatformDisplayEXT"));
};

struct EglContext::Gl : GlFunctions {};

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string eglErrorText(EGLint e) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(e));
  return std::string("EGL error ") + hex;
}

}  // namespace

EglContext::EglContext(int width, int height) {
  try {
    lib_ = std::make_unique<Library>();
  } catch (const ContextError& e) {
    throw ContextError(std::string("EGL is not available: ") + e.what());
  }
  try {
    create(width, height);
  } catch (...) {
    destroy();
    throw;
  }
  keepLoadedLibrariesForSanitizers();
}

void EglContext::create(int width, int height) {
  const char* clientExtensions = lib_->queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!lib_->getPlatformDisplay || !hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
    throw ContextError("EGL (" + lib_->so.name() +
                       ") has no surfaceless platform (EGL_MESA_platform_surfaceless)");
  display_ = lib_->getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  auto fail = [&](const std::string& what) {
    throw ContextError("EGL surfaceless: " + what + " (" + eglErrorText(lib_->getError()) + ")");
  };
  if (display_ == EGL_NO_DISPLAY) fail("no display");
  if (!lib_->initialize(display_, &major, &minor)) {
    display_ = nullptr;
    fail("the display could not be initialised");
  }
  const char* displayExtensions = lib_->queryString(display_, EGL_EXTENSIONS);
  if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context"))
    fail("no EGL_KHR_surfaceless_context");
  if (!lib_->bindApi(EGL_OPENGL_API)) fail("desktop OpenGL is not supported");

  // With EGL_KHR_no_config_context no config is needed; otherwise take any GL-capable one.
  EGLConfig config = nullptr;
  if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                       EGL_NONE};
    EGLint count = 0;
    if (!lib_->chooseConfig(display_, configAttributes, &config, 1, &count) || count < 1)
      fail("no OpenGL config");
  }
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      3,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  context_ = lib_->createContext(display_, config, EGL_NO_CONTEXT, contextAttributes);
  if (context_ == EGL_NO_CONTEXT) fail("could not create an OpenGL 3.3 core profile context");
  makeCurrent();
  gl_ = std::make_unique<Gl>();
  gl_->load([this](const char* name) { return getProcAddress(name); });
  resize(width, height);
}

EglContext::~EglContext() {
  destroy();
}

void EglContext::destroy() {
  if (context_) {
    if (gl_) {
      makeCurrent();
      releaseFramebuffer();
    }
    releaseIfCurrent();
    lib_->destroyContext(display_, context_);
    context_ = nullptr;
  }
  if (display_) lib_->terminate(display_);
  display_ = nullptr;
}

void EglContext::release() {
  lib_->makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void EglContext::bind() {
  if (!lib_->makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw ContextError("eglMakeCurrent failed (" + eglErrorText(lib_->getError()) + ")");
}

void* EglContext::getProcAddress(const char* name) {
  // Mesa resolves core functions too (EGL_KHR_get_all_proc_addresses).
  return reinterpret_cast<void*>(lib_->getProcAddress(name));
}

void EglContext::releaseFramebuffer() {
  if (!gl_) return;
  if (framebuffer_) gl_->DeleteFramebuffers(1, &framebuffer_);
  if (colorBuffer_) gl_->DeleteRenderbuffers(1, &colorBuffer_);
  if (depthBuffer_) gl_->DeleteRenderbuffers(1, &depthBuffer_);
  framebuffer_ = colorBuffer_ = depthBuffer_ = 0;
}

void EglContext::resize(int width, int height) {
  if (width < 1 || height < 1) throw ContextError("EGL: framebuffer size must be positive");
  if (width == width_ && height == height_ && framebuffer_) return;
  makeCurrent();
  releaseFramebuffer();
  const GlFunctions& gl = *gl_;
  gl.GenRenderbuffers(1, &colorBuffer_);
  gl.BindRenderbuffer(GL_RENDERBUFFER, colorBuffer_);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl.GenRenderbuffers(1, &depthBuffer_);
  gl.BindRenderbuffer(GL_RENDERBUFFER, depthBuffer_);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  gl.GenFramebuffers(1, &framebuffer_);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer_);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
  const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl.check("creating the EGL framebuffer");
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("EGL: framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete");
  width_ = width;
  height_ = height;
}

}  // namespace weft::render
