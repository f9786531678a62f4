#pragma once
// The OpenGL 4.5 core entry points sortlast uses, loaded through the active backend's
// GetProcAddress (OSMesaGetProcAddress or eglGetProcAddress). Nothing calls gl* symbols directly:
// libOSMesa and glvnd's libOpenGL both export them, and a binary linking both would call whichever
// the loader found first.
#include <functional>
#include <string>

#include <GL/glcorearb.h>

namespace sortlast {

// GL 1.1 entry points get their pointer types here: when OSMesa's GL/gl.h comes first it defines
// GL_VERSION_1_1, and glcorearb.h then skips these typedefs.
using PfnGenTextures = void(APIENTRYP)(GLsizei, GLuint*);
using PfnDeleteTextures = void(APIENTRYP)(GLsizei, const GLuint*);
using PfnBindTexture = void(APIENTRYP)(GLenum, GLuint);
using PfnDrawArrays = void(APIENTRYP)(GLenum, GLint, GLsizei);

// X(name without the gl prefix, PFN type)
#define SORTLAST_GL_FUNCTIONS(X)                                \
  X(GetError, PFNGLGETERRORPROC)                                \
  X(GetString, PFNGLGETSTRINGPROC)                              \
  X(GetStringi, PFNGLGETSTRINGIPROC)                            \
  X(GetIntegerv, PFNGLGETINTEGERVPROC)                          \
  X(Viewport, PFNGLVIEWPORTPROC)                                \
  X(Scissor, PFNGLSCISSORPROC)                                  \
  X(Enable, PFNGLENABLEPROC)                                    \
  X(Disable, PFNGLDISABLEPROC)                                  \
  X(StencilFunc, PFNGLSTENCILFUNCPROC)                          \
  X(StencilOp, PFNGLSTENCILOPPROC)                              \
  X(StencilMask, PFNGLSTENCILMASKPROC)                          \
  X(BlendFunc, PFNGLBLENDFUNCPROC)                              \
  X(ClearColor, PFNGLCLEARCOLORPROC)                            \
  X(Clear, PFNGLCLEARPROC)                                      \
  X(Finish, PFNGLFINISHPROC)                                    \
  X(FrontFace, PFNGLFRONTFACEPROC)                              \
  X(PixelStorei, PFNGLPIXELSTOREIPROC)                          \
  X(ReadPixels, PFNGLREADPIXELSPROC)                            \
  X(GenTextures, PfnGenTextures)                          \
  X(DeleteTextures, PfnDeleteTextures)                    \
  X(BindTexture, PfnBindTexture)                          \
  X(ActiveTexture, PFNGLACTIVETEXTUREPROC)                      \
  X(TexParameteri, PFNGLTEXPARAMETERIPROC)                      \
  X(TexImage1D, PFNGLTEXIMAGE1DPROC)                            \
  X(TexImage2D, PFNGLTEXIMAGE2DPROC)                            \
  X(TexImage3D, PFNGLTEXIMAGE3DPROC)                            \
  X(TexSubImage3D, PFNGLTEXSUBIMAGE3DPROC)                      \
  X(GenFramebuffers, PFNGLGENFRAMEBUFFERSPROC)                  \
  X(DeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)            \
  X(BindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                  \
  X(FramebufferTexture2D, PFNGLFRAMEBUFFERTEXTURE2DPROC)        \
  X(CheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC)    \
  X(CreateShader, PFNGLCREATESHADERPROC)                        \
  X(ShaderSource, PFNGLSHADERSOURCEPROC)                        \
  X(CompileShader, PFNGLCOMPILESHADERPROC)                      \
  X(GetShaderiv, PFNGLGETSHADERIVPROC)                          \
  X(GetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                \
  X(DeleteShader, PFNGLDELETESHADERPROC)                        \
  X(CreateProgram, PFNGLCREATEPROGRAMPROC)                      \
  X(AttachShader, PFNGLATTACHSHADERPROC)                        \
  X(LinkProgram, PFNGLLINKPROGRAMPROC)                          \
  X(GetProgramiv, PFNGLGETPROGRAMIVPROC)                        \
  X(GetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)              \
  X(UseProgram, PFNGLUSEPROGRAMPROC)                            \
  X(DeleteProgram, PFNGLDELETEPROGRAMPROC)                      \
  X(GetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)            \
  X(Uniform1i, PFNGLUNIFORM1IPROC)                              \
  X(Uniform1f, PFNGLUNIFORM1FPROC)                              \
  X(Uniform2f, PFNGLUNIFORM2FPROC)                              \
  X(Uniform3f, PFNGLUNIFORM3FPROC)                              \
  X(Uniform2d, PFNGLUNIFORM2DPROC)                              \
  X(Uniform3d, PFNGLUNIFORM3DPROC)                              \
  X(UniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)                \
  X(GenVertexArrays, PFNGLGENVERTEXARRAYSPROC)                  \
  X(BindVertexArray, PFNGLBINDVERTEXARRAYPROC)                  \
  X(DeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)            \
  X(GenBuffers, PFNGLGENBUFFERSPROC)                            \
  X(BindBuffer, PFNGLBINDBUFFERPROC)                            \
  X(BufferData, PFNGLBUFFERDATAPROC)                            \
  X(DeleteBuffers, PFNGLDELETEBUFFERSPROC)                      \
  X(VertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC)          \
  X(EnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC)  \
  X(DrawArrays, PfnDrawArrays)                                  \
  X(ColorMask, PFNGLCOLORMASKPROC)                              \
  X(BlendEquation, PFNGLBLENDEQUATIONPROC)                      \
  X(DrawArraysInstanced, PFNGLDRAWARRAYSINSTANCEDPROC)          \
  X(VertexAttribDivisor, PFNGLVERTEXATTRIBDIVISORPROC)          \
  X(TexStorage2D, PFNGLTEXSTORAGE2DPROC)                        \
  X(BindImageTexture, PFNGLBINDIMAGETEXTUREPROC)                \
  X(MemoryBarrier, PFNGLMEMORYBARRIERPROC)                      \
  X(TextureBarrier, PFNGLTEXTUREBARRIERPROC)                    \
  X(GenQueries, PFNGLGENQUERIESPROC)                            \
  X(DeleteQueries, PFNGLDELETEQUERIESPROC)                      \
  X(BeginQuery, PFNGLBEGINQUERYPROC)                            \
  X(EndQuery, PFNGLENDQUERYPROC)                                \
  X(GetQueryObjectuiv, PFNGLGETQUERYOBJECTUIVPROC)              \
  X(Uniform1ui, PFNGLUNIFORM1UIPROC)                            \
  X(Uniform4i, PFNGLUNIFORM4IPROC)                              \
  X(GetTexImage, PFNGLGETTEXIMAGEPROC)                          \
  X(CopyImageSubData, PFNGLCOPYIMAGESUBDATAPROC)                \
  X(DrawBuffers, PFNGLDRAWBUFFERSPROC)                          \
  X(BindBufferBase, PFNGLBINDBUFFERBASEPROC)                    \
  X(ReadBuffer, PFNGLREADBUFFERPROC)                            \
  X(DispatchCompute, PFNGLDISPATCHCOMPUTEPROC)                  \
  X(GetBufferSubData, PFNGLGETBUFFERSUBDATAPROC)                \
  X(Uniform4f, PFNGLUNIFORM4FPROC)                              \
  X(GetUniformfv, PFNGLGETUNIFORMFVPROC)                        \
  X(GetUniformiv, PFNGLGETUNIFORMIVPROC)                        \
  X(GetUniformuiv, PFNGLGETUNIFORMUIVPROC)                      \
  X(GetQueryObjectui64v, PFNGLGETQUERYOBJECTUI64VPROC)          \
  X(FenceSync, PFNGLFENCESYNCPROC)                              \
  X(ClientWaitSync, PFNGLCLIENTWAITSYNCPROC)                    \
  X(DeleteSync, PFNGLDELETESYNCPROC)                            \
  X(MapBufferRange, PFNGLMAPBUFFERRANGEPROC)                    \
  X(UnmapBuffer, PFNGLUNMAPBUFFERPROC)                          \
  X(Flush, PFNGLFLUSHPROC)

struct GlApi {
#define SORTLAST_GL_MEMBER(name, type) type name = nullptr;
  SORTLAST_GL_FUNCTIONS(SORTLAST_GL_MEMBER)
#undef SORTLAST_GL_MEMBER

  // Loads every entry point; throws std::runtime_error naming the first one missing.
  void load(const std::function<void*(const char*)>& get_proc);
  // Throws std::runtime_error if glGetError reports an error, naming `what`.
  void check(const char* what) const;
};

}  // namespace sortlast
