// The OpenGL 4.5 core functions the renderer calls, loaded by name through OSMesa.
//
// No GLEW or glad: the renderer uses a few dozen entry points, listed once in RENDER_GL_FUNCTIONS
// and loaded into a table of pointers. Only libOSMesa is linked; Mesa's libGL beside it would
// resolve gl* symbols to a dispatch table that sees no OSMesa context.
#pragma once

#include <GL/glcorearb.h>

namespace render {

// X(type, name): the entry point "gl" #name with the pointer type from glcorearb.h.
#define RENDER_GL_FUNCTIONS(X)                                                 \
  X(PFNGLGETSTRINGPROC, GetString)                                             \
  X(PFNGLGETERRORPROC, GetError)                                               \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                         \
  X(PFNGLVIEWPORTPROC, Viewport)                                               \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                           \
  X(PFNGLCLEARPROC, Clear)                                                     \
  X(PFNGLENABLEPROC, Enable)                                                   \
  X(PFNGLDISABLEPROC, Disable)                                                 \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                             \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                         \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                           \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                           \
  X(PFNGLFINISHPROC, Finish)                                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                                       \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                       \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                     \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                         \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                               \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                       \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                     \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                       \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                         \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                             \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                     \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                             \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                             \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                             \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                             \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                 \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                           \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                           \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                   \
  X(PFNGLBUFFERDATAPROC, BufferData)                                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                     \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                         \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                 \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                         \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                         \
  X(PFNGLDRAWARRAYSINSTANCEDBASEINSTANCEPROC, DrawArraysInstancedBaseInstance) \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                         \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                         \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                     \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                           \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                     \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                                   \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                   \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                 \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                 \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                 \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                           \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                         \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)

// Call as gl.Clear(GL_COLOR_BUFFER_BIT). Every pointer is non-null once load() returned.
struct GlApi {
#define RENDER_GL_MEMBER(type, name) type name = nullptr;
  RENDER_GL_FUNCTIONS(RENDER_GL_MEMBER)
#undef RENDER_GL_MEMBER

  using Proc = void (*)();
  using GetProc = Proc (*)(const char* name);
  // Loads every entry point; throws std::runtime_error naming the first one that is missing.
  void load(GetProc getProc);
};

}  // namespace render
