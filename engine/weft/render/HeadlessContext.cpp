#include <weft/render/HeadlessContext.h>

#include <weft/render/EglContext.h>
#include <weft/render/GlFunctions.h>
#include <weft/render/OsMesaContext.h>
#include <weft/render/RenderError.h>

#include <ostream>

namespace weft::render {

bool parseHeadlessBackend(const std::string& text, HeadlessBackend& backend) {
  if (text == "auto")
    backend = HeadlessBackend::Auto;
  else if (text == "osmesa")
    backend = HeadlessBackend::OsMesa;
  else if (text == "egl")
    backend = HeadlessBackend::Egl;
  else
    return false;
  return true;
}

std::unique_ptr<RenderContext> createHeadlessContext(int width, int height, HeadlessBackend backend,
                                                     std::ostream* log) {
  std::unique_ptr<RenderContext> context;
  std::string reasons;
  if (backend == HeadlessBackend::OsMesa || backend == HeadlessBackend::Auto) {
    try {
      context = std::make_unique<OsMesaContext>(width, height);
    } catch (const ContextError& e) {
      reasons = e.what();
    }
  }
  if (!context && (backend == HeadlessBackend::Egl || backend == HeadlessBackend::Auto)) {
    try {
      context = std::make_unique<EglContext>(width, height);
    } catch (const ContextError& e) {
      reasons += (reasons.empty() ? "" : "; ") + std::string(e.what());
    }
  }
  if (!context) throw ContextError("no headless OpenGL 3.3 context: " + reasons);
  if (log) {
    auto getString = reinterpret_cast<PFNGLGETSTRINGPROC>(context->getProcAddress("glGetString"));
    auto text = [&](GLenum name) {
      const GLubyte* s = getString ? getString(name) : nullptr;
      return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    *log << "OpenGL: backend " << context->backendName() << ", GL_VERSION " << text(GL_VERSION)
         << ", GL_RENDERER " << text(GL_RENDERER) << "\n";
  }
  return context;
}

}  // namespace weft::render
