// The OpenGL 4.5 core entry points blurcull uses, as a table of function
// pointers filled by the context that loaded them (gl_context.hpp).
//
// No loader library: libepoxy aborts under OSMesa, glad is not packaged as a
// library on Debian 12, and libOSMesa exports only part of GL directly, so
// every entry point comes from eglGetProcAddress or OSMesaGetProcAddress (or,
// for a window's context, glfwGetProcAddress).
// To use another function, add one X(...) line below.
#pragma once

#include <GL/glcorearb.h>

// X(type of the pointer, name without the gl prefix)
#define BLURCULL_GL_FUNCTIONS(X)                                   \
    X(PFNGLGETERRORPROC, GetError)                                 \
    X(PFNGLGETSTRINGPROC, GetString)                               \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                           \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                       \
    X(PFNGLFINISHPROC, Finish)                                     \
    X(PFNGLCREATESHADERPROC, CreateShader)                         \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                         \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                       \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                           \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                 \
    X(PFNGLDELETESHADERPROC, DeleteShader)                         \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                       \
    X(PFNGLATTACHSHADERPROC, AttachShader)                         \
    X(PFNGLDETACHSHADERPROC, DetachShader)                         \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                           \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                         \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)               \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                       \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                             \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)             \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                               \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                             \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                               \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                               \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                             \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                       \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                             \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                     \
    X(PFNGLBUFFERDATAPROC, BufferData)                             \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                       \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                 \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                   \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                       \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                   \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)             \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                   \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)     \
    X(PFNGLGENTEXTURESPROC, GenTextures)                           \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                     \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                           \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                         \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                       \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                       \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                   \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)         \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                   \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)             \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                   \
    X(PFNGLVIEWPORTPROC, Viewport)                                 \
    X(PFNGLCLEARCOLORPROC, ClearColor)                             \
    X(PFNGLCLEARPROC, Clear)                                       \
    X(PFNGLREADPIXELSPROC, ReadPixels)                             \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                             \
    X(PFNGLDRAWARRAYSINDIRECTPROC, DrawArraysIndirect)             \
    X(PFNGLENABLEPROC, Enable)                                     \
    X(PFNGLDISABLEPROC, Disable)                                   \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                               \
    X(PFNGLCLIPCONTROLPROC, ClipControl)                           \
    X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv)                     \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                       \
    X(PFNGLTEXSTORAGE2DMULTISAMPLEPROC, TexStorage2DMultisample)   \
    X(PFNGLMINSAMPLESHADINGPROC, MinSampleShading)                 \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                       \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                               \
    X(PFNGLCOLORMASKPROC, ColorMask)                               \
    X(PFNGLDEPTHMASKPROC, DepthMask)                               \
    X(PFNGLCLEARBUFFERDATAPROC, ClearBufferData)                   \
    X(PFNGLCOPYBUFFERSUBDATAPROC, CopyBufferSubData)               \
    X(PFNGLGENQUERIESPROC, GenQueries)                             \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                       \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                             \
    X(PFNGLENDQUERYPROC, EndQuery)                                 \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

namespace blurcull::gl {

// Every pointer is non-null once a context has loaded the table.
struct Functions {
#define BLURCULL_GL_DECLARE(type, name) type name = nullptr;
    BLURCULL_GL_FUNCTIONS(BLURCULL_GL_DECLARE)
#undef BLURCULL_GL_DECLARE
};

}  // namespace blurcull::gl
