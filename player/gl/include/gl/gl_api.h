#pragma once
// One table of GL entry points, loaded at run time from whichever platform created the context.
// libOSMesa and libGLESv2 both export gl* symbols, so the render code never calls them directly:
// it calls gl.Name(...), and the platform fills the table through its GetProcAddress.
#define GL_GLES_PROTOTYPES 0
#include <GLES3/gl31.h>
// gl2ext.h needs the types gl31.h declares.
#include <GLES2/gl2ext.h>

#include "platform/platform.h"

#include <memory>
#include <string>

namespace gl {

// The tables are laid out by hand, two entry points to a line where they fit.
// clang-format off
// Entry points every supported context has: GLES 3.1, or desktop GL 4.5 core running ES 3.1 shaders.
#define PLAYER_GL_REQUIRED(X)                                                         \
  X(PFNGLGETSTRINGPROC, GetString) X(PFNGLGETSTRINGIPROC, GetStringi)                 \
  X(PFNGLGETINTEGERVPROC, GetIntegerv) X(PFNGLGETERRORPROC, GetError)                 \
  X(PFNGLENABLEPROC, Enable) X(PFNGLDISABLEPROC, Disable)                             \
  X(PFNGLVIEWPORTPROC, Viewport) X(PFNGLCLEARPROC, Clear) X(PFNGLDRAWARRAYSPROC, DrawArrays) \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv) X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv)  \
  X(PFNGLDEPTHFUNCPROC, DepthFunc) X(PFNGLUNIFORM3FVPROC, Uniform3fv)                  \
  X(PFNGLDEPTHMASKPROC, DepthMask) X(PFNGLCOLORMASKPROC, ColorMask)                   \
  X(PFNGLCULLFACEPROC, CullFace) X(PFNGLFRONTFACEPROC, FrontFace)                     \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                                     \
  X(PFNGLGENBUFFERSPROC, GenBuffers) X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)         \
  X(PFNGLBINDBUFFERPROC, BindBuffer) X(PFNGLBUFFERDATAPROC, BufferData)               \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData) X(PFNGLBINDBUFFERBASEPROC, BindBufferBase) \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                        \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                  \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                        \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                        \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                              \
  X(PFNGLGENTEXTURESPROC, GenTextures) X(PFNGLDELETETEXTURESPROC, DeleteTextures)     \
  X(PFNGLBINDTEXTUREPROC, BindTexture) X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)         \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D) X(PFNGLTEXPARAMETERIPROC, TexParameteri)   \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap) X(PFNGLACTIVETEXTUREPROC, ActiveTexture) \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                                      \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                        \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                  \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                        \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                              \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                          \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers) X(PFNGLREADBUFFERPROC, ReadBuffer) X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer) \
  X(PFNGLREADPIXELSPROC, ReadPixels) X(PFNGLPIXELSTOREIPROC, PixelStorei)             \
  X(PFNGLCREATESHADERPROC, CreateShader) X(PFNGLSHADERSOURCEPROC, ShaderSource)       \
  X(PFNGLCOMPILESHADERPROC, CompileShader) X(PFNGLGETSHADERIVPROC, GetShaderiv)       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) X(PFNGLDELETESHADERPROC, DeleteShader) \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram) X(PFNGLATTACHSHADERPROC, AttachShader)     \
  X(PFNGLLINKPROGRAMPROC, LinkProgram) X(PFNGLGETPROGRAMIVPROC, GetProgramiv)         \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                    \
  X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary) X(PFNGLPROGRAMBINARYPROC, ProgramBinary) \
  X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri)                                    \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram) X(PFNGLUSEPROGRAMPROC, UseProgram)         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                  \
  X(PFNGLUNIFORM1IPROC, Uniform1i) X(PFNGLUNIFORM1FPROC, Uniform1f)                   \
  X(PFNGLUNIFORM2IPROC, Uniform2i) X(PFNGLUNIFORM4FVPROC, Uniform4fv)                 \
  X(PFNGLUNIFORM4FPROC, Uniform4f) X(PFNGLUNIFORM4IPROC, Uniform4i) X(PFNGLSCISSORPROC, Scissor) \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                                      \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                      \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute) X(PFNGLMEMORYBARRIERPROC, MemoryBarrier) \
  X(PFNGLDRAWELEMENTSPROC, DrawElements) X(PFNGLFINISHPROC, Finish)                   \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor) X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced) \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                                    \
  X(PFNGLGENQUERIESPROC, GenQueries) X(PFNGLDELETEQUERIESPROC, DeleteQueries)         \
  X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv)

// Entry points that depend on an extension; null where the context lacks it.
#define PLAYER_GL_OPTIONAL(X)                                       \
  X(PFNGLQUERYCOUNTEREXTPROC, QueryCounter)                         \
  X(PFNGLGETQUERYOBJECTUI64VEXTPROC, GetQueryObjectui64v)           \
  X(PFNGLDEBUGMESSAGECALLBACKKHRPROC, DebugMessageCallback)         \
  X(PFNGLDEBUGMESSAGECONTROLKHRPROC, DebugMessageControl)         \
  X(PFNGLGETGRAPHICSRESETSTATUSKHRPROC, GetGraphicsResetStatus)
// clang-format on

struct Api {
#define PLAYER_GL_MEMBER(type, name) type name = nullptr;
  PLAYER_GL_REQUIRED(PLAYER_GL_MEMBER)
  PLAYER_GL_OPTIONAL(PLAYER_GL_MEMBER)
#undef PLAYER_GL_MEMBER
};

// The table the render code calls through; one context is current per process.
extern Api api;

// Fills `api` for the platform's current context. Optional entry points are tried under each
// suffix ("" for core, "EXT", "KHR"). Returns false and names the first missing required entry
// point in `error`.
bool load(const platform::Platform& platform, std::string& error);

}  // namespace gl
