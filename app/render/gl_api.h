// The OpenGL 3.3 core functions the renderer calls, as pointers loaded at run time from the
// current context's proc-address function (OSMesa offscreen, GLFW in the viewer). Going
// through pointers, never through libGL's exported symbols, lets one renderer run on either
// context without the two GL libraries' symbols clashing.
#pragma once

#include <GL/glcorearb.h>

#include "app/render/gl_loader.h"

namespace dynamesh::gl {

// X(UPPERCASE_NAME, Name): the pointer gl::Name has type PFNGL<UPPERCASE_NAME>PROC.
#define DYNAMESH_GL_FUNCTIONS(X)                                    \
  X(ACTIVETEXTURE, ActiveTexture)                                   \
  X(ATTACHSHADER, AttachShader)                                     \
  X(BINDBUFFER, BindBuffer)                                         \
  X(BINDFRAMEBUFFER, BindFramebuffer)                               \
  X(BINDRENDERBUFFER, BindRenderbuffer)                             \
  X(BINDTEXTURE, BindTexture)                                       \
  X(BINDVERTEXARRAY, BindVertexArray)                               \
  X(BLITFRAMEBUFFER, BlitFramebuffer)                               \
  X(BUFFERDATA, BufferData)                                         \
  X(BUFFERSUBDATA, BufferSubData)                                   \
  X(CHECKFRAMEBUFFERSTATUS, CheckFramebufferStatus)                 \
  X(CLEAR, Clear)                                                   \
  X(CLEARCOLOR, ClearColor)                                         \
  X(COMPILESHADER, CompileShader)                                   \
  X(CREATEPROGRAM, CreateProgram)                                   \
  X(CREATESHADER, CreateShader)                                     \
  X(DELETEBUFFERS, DeleteBuffers)                                   \
  X(DELETEFRAMEBUFFERS, DeleteFramebuffers)                         \
  X(DELETEPROGRAM, DeleteProgram)                                   \
  X(DELETERENDERBUFFERS, DeleteRenderbuffers)                       \
  X(DELETESHADER, DeleteShader)                                     \
  X(DELETETEXTURES, DeleteTextures)                                 \
  X(DELETEVERTEXARRAYS, DeleteVertexArrays)                         \
  X(DEPTHFUNC, DepthFunc)                                           \
  X(DISABLE, Disable)                                               \
  X(DRAWELEMENTS, DrawElements)                                     \
  X(ENABLE, Enable)                                                 \
  X(ENABLEVERTEXATTRIBARRAY, EnableVertexAttribArray)               \
  X(FINISH, Finish)                                                 \
  X(FRAMEBUFFERRENDERBUFFER, FramebufferRenderbuffer)               \
  X(GENBUFFERS, GenBuffers)                                         \
  X(GENFRAMEBUFFERS, GenFramebuffers)                               \
  X(GENRENDERBUFFERS, GenRenderbuffers)                             \
  X(GENTEXTURES, GenTextures)                                       \
  X(GENVERTEXARRAYS, GenVertexArrays)                               \
  X(GETERROR, GetError)                                             \
  X(GETINTEGERV, GetIntegerv)                                       \
  X(GETPROGRAMINFOLOG, GetProgramInfoLog)                           \
  X(GETPROGRAMIV, GetProgramiv)                                     \
  X(GETSHADERINFOLOG, GetShaderInfoLog)                             \
  X(GETSHADERIV, GetShaderiv)                                       \
  X(GETSTRING, GetString)                                           \
  X(GETUNIFORMLOCATION, GetUniformLocation)                         \
  X(LINKPROGRAM, LinkProgram)                                       \
  X(PIXELSTOREI, PixelStorei)                                       \
  X(READBUFFER, ReadBuffer)                                         \
  X(READPIXELS, ReadPixels)                                         \
  X(RENDERBUFFERSTORAGEMULTISAMPLE, RenderbufferStorageMultisample) \
  X(SHADERSOURCE, ShaderSource)                                     \
  X(TEXIMAGE2D, TexImage2D)                                         \
  X(TEXIMAGE3D, TexImage3D)                                         \
  X(TEXPARAMETERI, TexParameteri)                                   \
  X(UNIFORM1F, Uniform1f)                                           \
  X(UNIFORM1I, Uniform1i)                                           \
  X(UNIFORM2F, Uniform2f)                                           \
  X(UNIFORM3F, Uniform3f)                                           \
  X(UNIFORM4F, Uniform4f)                                           \
  X(UNIFORMMATRIX3FV, UniformMatrix3fv)                             \
  X(UNIFORMMATRIX4FV, UniformMatrix4fv)                             \
  X(USEPROGRAM, UseProgram)                                         \
  X(VERTEXATTRIBPOINTER, VertexAttribPointer)                       \
  X(VIEWPORT, Viewport)

#define DYNAMESH_GL_DECLARE(UPPER, Name) extern PFNGL##UPPER##PROC Name;
DYNAMESH_GL_FUNCTIONS(DYNAMESH_GL_DECLARE)
#undef DYNAMESH_GL_DECLARE

}  // namespace dynamesh::gl
