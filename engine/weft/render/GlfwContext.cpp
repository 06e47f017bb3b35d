#include <weft/render/GlfwContext.h>

#include <weft/render/RenderError.h>

#include "SharedLibrary.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <mutex>

namespace weft::render {
namespace {

// GLFW is process-wide: initialised with the first window, terminated with the last.
std::mutex glfwMutex;
int glfwUsers = 0;
std::string glfwLastError;

void recordGlfwError(int, const char* description) {
  glfwLastError = description ? description : "";
}

}  // namespace

GlfwContext::GlfwContext(const std::string& title, int width, int height, bool visible) {
  std::lock_guard<std::mutex> lock(glfwMutex);
  glfwSetErrorCallback(recordGlfwError);
  if (glfwUsers == 0 && !glfwInit())
    throw ContextError("GLFW cannot open a window (" + glfwLastError +
                       "); without a display use the headless backends");
  ++glfwUsers;
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    if (--glfwUsers == 0) glfwTerminate();
    throw ContextError("GLFW could not create an OpenGL 3.3 core window (" + glfwLastError + ")");
  }
  makeCurrent();
  keepLoadedLibrariesForSanitizers();
}

GlfwContext::~GlfwContext() {
  releaseIfCurrent();
  std::lock_guard<std::mutex> lock(glfwMutex);
  glfwDestroyWindow(window_);
  if (--glfwUsers == 0) glfwTerminate();
}

void GlfwContext::bind() {
  glfwMakeContextCurrent(window_);
}

void GlfwContext::release() {
  glfwMakeContextCurrent(nullptr);
}

void* GlfwContext::getProcAddress(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

int GlfwContext::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w;
}

int GlfwContext::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return h;
}

void GlfwContext::resize(int width, int height) {
  glfwSetWindowSize(window_, width, height);
}

void GlfwContext::present() {
  glfwSwapBuffers(window_);
}

}  // namespace weft::render
