// The OpenGL 3.3 core entry points the renderer uses, loaded at run time through a loader
// supplied by whoever owns the context (Qt or OSMesa). Internal to core/render.
#pragma once

#include <GL/glcorearb.h>

#include "core/render/gl_loader.h"

namespace handlab::render {

#define HANDLAB_GL_FUNCTIONS(X)                                              \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)                         \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                             \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                         \
  X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                         \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)

struct GlFunctions {
#define HANDLAB_GL_MEMBER(type, name) type name = nullptr;
  HANDLAB_GL_FUNCTIONS(HANDLAB_GL_MEMBER)
#undef HANDLAB_GL_MEMBER

  // Resolves every entry point; throws std::runtime_error naming the first one missing.
  explicit GlFunctions(const GlLoader& loader);
};

}  // namespace handlab::render
