#pragma once
// Weft's own table of the OpenGL 3.3 core functions the renderer uses, filled from the
// current backend's getProcAddress. libGL and libOSMesa both export gl* symbols, so calling
// GL through link-time symbols could reach the wrong implementation; every GL call in the
// renderer goes through a table loaded from the context it draws with.

#include <GL/glcorearb.h>  // types and PFN typedefs only (no GL_GLEXT_PROTOTYPES)

#include <functional>
#include <string>

namespace weft::render {

// X(type, name): `name` is the GL function without its "gl" prefix.
// clang-format off
#define WEFT_GL_FUNCTIONS(X)                                         \
  X(PFNGLGETSTRINGPROC, GetString)                                   \
  X(PFNGLGETERRORPROC, GetError)                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                               \
  X(PFNGLVIEWPORTPROC, Viewport)                                     \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                 \
  X(PFNGLCLEARPROC, Clear)                                           \
  X(PFNGLENABLEPROC, Enable)                                         \
  X(PFNGLDISABLEPROC, Disable)                                       \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                   \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                   \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                   \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                           \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                               \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                 \
  X(PFNGLFINISHPROC, Finish)                                         \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                 \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                 \
  X(PFNGLBUFFERDATAPROC, BufferData)                                 \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                       \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                 \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)       \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                 \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                             \
  X(PFNGLCREATESHADERPROC, CreateShader)                             \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                             \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                           \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                               \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                     \
  X(PFNGLDELETESHADERPROC, DeleteShader)                             \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                           \
  X(PFNGLATTACHSHADERPROC, AttachShader)                             \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                               \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                             \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                   \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                           \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                 \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                 \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                   \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                   \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                   \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                   \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                   \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                     \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                     \
  X(PFNGLGENTEXTURESPROC, GenTextures)                               \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                         \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                               \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                           \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                 \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                           \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                       \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                 \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                       \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)       \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)         \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                     \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                     \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)
// clang-format on

// A function address by its full GL name ("glClear"); null when unknown.
using GetProcAddress = std::function<void*(const char* name)>;

struct GlFunctions {
#define WEFT_GL_MEMBER(type, name) type name = nullptr;
  WEFT_GL_FUNCTIONS(WEFT_GL_MEMBER)
#undef WEFT_GL_MEMBER

  // Resolves every function; throws ContextError naming the first one the context lacks.
  void load(const GetProcAddress& getProcAddress);

  // Throws GlError naming `where` and every pending GL error; clears the error queue.
  void check(const char* where) const;
  std::string string(GLenum name) const;  // glGetString as text ("" when null)
};

const char* glErrorName(GLenum error);

}  // namespace weft::render
