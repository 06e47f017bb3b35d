#include <weft/render/GlFunctions.h>

#include <weft/render/RenderError.h>

namespace weft::render {

void GlFunctions::load(const GetProcAddress& getProcAddress) {
#define WEFT_GL_LOAD(type, name)                             \
  name = reinterpret_cast<type>(getProcAddress("gl" #name)); \
  if (!name) throw ContextError("OpenGL function gl" #name " is not available from the context");
  WEFT_GL_FUNCTIONS(WEFT_GL_LOAD)
#undef WEFT_GL_LOAD
}

void GlFunctions::check(const char* where) const {
  std::string errors;
  // Bounded: a lost context can report errors forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum e = GetError();
    if (e == GL_NO_ERROR) break;
    errors += (errors.empty() ? "" : ", ") + std::string(glErrorName(e));
  }
  if (!errors.empty()) throw GlError(std::string("OpenGL error after ") + where + ": " + errors);
}

std::string GlFunctions::string(GLenum name) const {
  const GLubyte* s = GetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

const char* glErrorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "unknown GL error";
  }
}

}  // namespace weft::render
