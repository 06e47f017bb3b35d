#pragma once
// Weft's own macro table (not Dear ImGui code): force-included (-include) into Debian's
// imgui_impl_opengl3.cpp, compiled with IMGUI_IMPL_OPENGL_LOADER_CUSTOM, it routes every gl*
// call of that backend through the editor's table, loaded from the current RenderContext (see
// EditorGl.h).

#include "EditorGl.h"

#define glActiveTexture weftEditorGl.ActiveTexture
#define glAttachShader weftEditorGl.AttachShader
#define glBindBuffer weftEditorGl.BindBuffer
#define glBindSampler weftEditorGl.BindSampler
#define glBindTexture weftEditorGl.BindTexture
#define glBindVertexArray weftEditorGl.BindVertexArray
#define glBlendEquation weftEditorGl.BlendEquation
#define glBlendEquationSeparate weftEditorGl.BlendEquationSeparate
#define glBlendFuncSeparate weftEditorGl.BlendFuncSeparate
#define glBufferData weftEditorGl.BufferData
#define glBufferSubData weftEditorGl.BufferSubData
#define glCompileShader weftEditorGl.CompileShader
#define glCreateProgram weftEditorGl.CreateProgram
#define glCreateShader weftEditorGl.CreateShader
#define glDeleteBuffers weftEditorGl.DeleteBuffers
#define glDeleteProgram weftEditorGl.DeleteProgram
#define glDeleteShader weftEditorGl.DeleteShader
#define glDeleteTextures weftEditorGl.DeleteTextures
#define glDeleteVertexArrays weftEditorGl.DeleteVertexArrays
#define glDetachShader weftEditorGl.DetachShader
#define glDisable weftEditorGl.Disable
#define glDrawElements weftEditorGl.DrawElements
#define glDrawElementsBaseVertex weftEditorGl.DrawElementsBaseVertex
#define glEnable weftEditorGl.Enable
#define glEnableVertexAttribArray weftEditorGl.EnableVertexAttribArray
#define glGenBuffers weftEditorGl.GenBuffers
#define glGenTextures weftEditorGl.GenTextures
#define glGenVertexArrays weftEditorGl.GenVertexArrays
#define glGetAttribLocation weftEditorGl.GetAttribLocation
#define glGetError weftEditorGl.GetError
#define glGetIntegerv weftEditorGl.GetIntegerv
#define glGetProgramInfoLog weftEditorGl.GetProgramInfoLog
#define glGetProgramiv weftEditorGl.GetProgramiv
#define glGetShaderInfoLog weftEditorGl.GetShaderInfoLog
#define glGetShaderiv weftEditorGl.GetShaderiv
#define glGetString weftEditorGl.GetString
#define glGetStringi weftEditorGl.GetStringi
#define glGetUniformLocation weftEditorGl.GetUniformLocation
#define glIsEnabled weftEditorGl.IsEnabled
#define glLinkProgram weftEditorGl.LinkProgram
#define glPixelStorei weftEditorGl.PixelStorei
#define glPolygonMode weftEditorGl.PolygonMode
#define glScissor weftEditorGl.Scissor
#define glShaderSource weftEditorGl.ShaderSource
#define glTexImage2D weftEditorGl.TexImage2D
#define glTexParameteri weftEditorGl.TexParameteri
#define glUniform1i weftEditorGl.Uniform1i
#define glUniformMatrix4fv weftEditorGl.UniformMatrix4fv
#define glUseProgram weftEditorGl.UseProgram
#define glVertexAttribPointer weftEditorGl.VertexAttribPointer
#define glViewport weftEditorGl.Viewport
