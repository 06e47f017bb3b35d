#pragma once
// The OpenGL functions the editor's own GL code and Dear ImGui's OpenGL3 backend call, loaded
// from the current RenderContext (a GLFW window or an OSMesa buffer). ImGui's backend normally
// loads GL from libGL through its bundled gl3w loader, which cannot reach OSMesa; the editor
// compiles Debian's backend source with IMGUI_IMPL_OPENGL_LOADER_CUSTOM and this header
// force-included, so every gl* call in it goes through this table instead (the same design as
// the renderer's GlFunctions).

#include <GL/glcorearb.h>

// X(type, name): `name` is the GL function without its "gl" prefix.
// clang-format off
#define WEFT_EDITOR_GL_FUNCTIONS(X)                                  \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                           \
  X(PFNGLATTACHSHADERPROC, AttachShader)                             \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                 \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                               \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                               \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                       \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                           \
  X(PFNGLBLENDEQUATIONSEPARATEPROC, BlendEquationSeparate)           \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                   \
  X(PFNGLBUFFERDATAPROC, BufferData)                                 \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                           \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                           \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                           \
  X(PFNGLCREATESHADERPROC, CreateShader)                             \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                           \
  X(PFNGLDELETESHADERPROC, DeleteShader)                             \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                         \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                 \
  X(PFNGLDETACHSHADERPROC, DetachShader)                             \
  X(PFNGLDISABLEPROC, Disable)                                       \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                             \
  X(PFNGLDRAWELEMENTSBASEVERTEXPROC, DrawElementsBaseVertex)         \
  X(PFNGLENABLEPROC, Enable)                                         \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)       \
  X(PFNGLFINISHPROC, Finish)                                         \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                 \
  X(PFNGLGENTEXTURESPROC, GenTextures)                               \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                       \
  X(PFNGLGETATTRIBLOCATIONPROC, GetAttribLocation)                   \
  X(PFNGLGETERRORPROC, GetError)                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                               \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                   \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                             \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                     \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                               \
  X(PFNGLGETSTRINGPROC, GetString)                                   \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                 \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                 \
  X(PFNGLISENABLEDPROC, IsEnabled)                                   \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                               \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                               \
  X(PFNGLPOLYGONMODEPROC, PolygonMode)                               \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                 \
  X(PFNGLSCISSORPROC, Scissor)                                       \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                             \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                 \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                           \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                   \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                     \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                 \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)               \
  X(PFNGLVIEWPORTPROC, Viewport)                                     \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                 \
  X(PFNGLCLEARPROC, Clear)                                           \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                       \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                       \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                 \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)             \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)       \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)         \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                     \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                     \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)
// clang-format on

struct WeftEditorGl {
#define WEFT_EDITOR_GL_MEMBER(type, name) type name;
  WEFT_EDITOR_GL_FUNCTIONS(WEFT_EDITOR_GL_MEMBER)
#undef WEFT_EDITOR_GL_MEMBER
};

// The table in use (the one loaded last). A plain global with C++ linkage: ImGui's backend
// reads it through the macros of ImGuiBackendGlRouting.h.
extern WeftEditorGl weftEditorGl;

namespace weft::render {
class RenderContext;
}

namespace weft::editor {
// Loads the table from `context` (made current). Throws render::ContextError naming the first
// function the context lacks.
void loadEditorGl(render::RenderContext& context);
}  // namespace weft::editor
