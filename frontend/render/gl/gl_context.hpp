// A headless OpenGL 4.5 core context for tests and the GL backend: EGL
// surfaceless (Mesa's EGL_PLATFORM_SURFACELESS_MESA, no window system, no
// config, no surface) first, OSMesa as the fallback. Both libraries are opened
// at run time, so a binary that links this still starts where neither is
// installed; it only fails, with a message, when it asks for a context.
//
// A surfaceless context has no usable default framebuffer: render into an FBO.
// HeadlessContext::from_current wraps instead a context someone else made and
// made current (`blurcull view`'s GLFW window), so the same renderer draws there.
//
// Lifetimes (docs/gl-backend.md, "Contexts"):
// - Any number of contexts may live at once, made and destroyed in any order.
//   Every EGL context is on the process's one surfaceless display, which is
//   initialised by the first live context and terminated by the last to go.
//   A context is current after create() and after make_current(); destroying
//   another context leaves it current. With several alive, call make_current()
//   before using one.
// - Destroy a GL object (Program, Buffer, ...) while its context is current:
//   glDelete* acts on whichever context is current.
// - Destroy every context and GL object before main returns (not from a
//   static's destructor): the drivers register exit handlers while they
//   initialise (NVIDIA's EGL in eglInitialize) that shut them down before
//   such destructors run. As a guard, once exit has begun the destructors
//   here release nothing (driver_usable() is false) and make_current throws,
//   so a straggler leaks instead of crashing the exit.
#pragma once

#include "render/gl/gl_functions.hpp"

#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace blurcull::gl {

// Any failure to create a context, compile a shader or run GL.
class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// current: made and owned by the caller, see HeadlessContext::from_current.
enum class ContextKind { egl_surfaceless, osmesa, current };

const char* context_kind_name(ContextKind kind);

// Parses "egl" or "osmesa"; throws GlError naming the bad value.
ContextKind parse_context_kind(std::string_view name);

class HeadlessContext {
public:
    // The kind named by the environment variable BLURCULL_GL_CONTEXT ("egl" or
    // "osmesa") if set, else EGL surfaceless, then OSMesa. Throws GlError
    // listing why each tried kind failed.
    static HeadlessContext create();
    // Exactly this kind; throws GlError when it cannot be created.
    static HeadlessContext create(ContextKind kind);
    // The context current on the calling thread, made by the caller (e.g. a
    // GLFW window), with its entry points loaded by `loader` (e.g.
    // glfwGetProcAddress; `loader_name` names it in errors). The caller keeps
    // it current and alive while this object is used; make_current() does
    // nothing and destruction does not destroy it. Throws GlError when no
    // context is current, an entry point is missing or it is not OpenGL 4.5.
    static HeadlessContext from_current(void (*(*loader)(const char*))(), const char* loader_name);

    HeadlessContext(HeadlessContext&& other) noexcept;
    HeadlessContext& operator=(HeadlessContext&& other) noexcept;
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;
    ~HeadlessContext();

    // The entry points, loaded for this context; every pointer is set.
    const Functions& gl() const;
    ContextKind kind() const;
    std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    // Whether renderer() names a software rasterizer (llvmpipe, softpipe,
    // swrast): GL on the CPU, slower than the cpu backend, and with timer
    // queries that do not time its work.
    bool software() const;
    std::string version() const;   // GL_VERSION
    // Makes this context current on the calling thread (create() already did).
    void make_current() const;
    // make_current for a destructor about to delete this context's objects:
    // never throws (a failure leaves the current context as it was) and does
    // nothing once the process is exiting (driver_usable()).
    void make_current_for_release() const noexcept;

    // How many contexts create() has made in this process so far (not
    // from_current's): for tests that count a render's contexts. With the
    // environment variable BLURCULL_GL_TRACE_CONTEXTS=1 each also prints a
    // line "blurcull gl: context N made (kind, renderer)" on stderr.
    static std::size_t contexts_made();

    struct State;

private:
    explicit HeadlessContext(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

// False once the process has begun exiting after a context was made (see
// the top of this file): the GL driver may be shut down, so nothing may call it.
bool driver_usable() noexcept;

// Throws GlError("<what>: GL error 0x....") when glGetError reports one.
void check_gl(const Functions& gl, const char* what);

// One shader stage given as the strings glShaderSource concatenates, e.g.
// {kernel_glsl(), my_main}.
struct ShaderStage {
    GLenum type = GL_COMPUTE_SHADER;
    std::vector<std::string_view> sources;
};

// A linked program object; deleted with this object.
class Program {
public:
    // Compiles and links; throws GlError with the compiler's or linker's log.
    Program(const Functions& gl, const std::vector<ShaderStage>& stages);
    Program(Program&& other) noexcept;
    Program& operator=(Program&&) = delete;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
    ~Program();
    GLuint id() const { return id_; }

private:
    const Functions* gl_;
    GLuint id_;
};

// An immutable-storage 2D texture: GL_TEXTURE_2D, or GL_TEXTURE_2D_MULTISAMPLE
// with `samples` samples at fixed locations; deleted with this object.
class Texture {
public:
    Texture(const Functions& gl, GLenum target, GLenum format, int width, int height, int samples = 0);
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;
    ~Texture();
    GLuint id() const { return id_; }
    GLenum target() const { return target_; }

private:
    const Functions* gl_;
    GLenum target_;
    GLuint id_ = 0;
};

// A framebuffer object; deleted with this object.
class Framebuffer {
public:
    explicit Framebuffer(const Functions& gl);
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;
    ~Framebuffer();
    GLuint id() const { return id_; }

private:
    const Functions* gl_;
    GLuint id_ = 0;
};

// A vertex array object (the core profile draws with one bound, even with
// no attributes); deleted with this object.
class VertexArray {
public:
    explicit VertexArray(const Functions& gl);
    VertexArray(VertexArray&& other) noexcept;
    VertexArray& operator=(VertexArray&&) = delete;
    VertexArray(const VertexArray&) = delete;
    VertexArray& operator=(const VertexArray&) = delete;
    ~VertexArray();
    GLuint id() const { return id_; }

private:
    const Functions* gl_;
    GLuint id_ = 0;
};

// A buffer object (e.g. an SSBO) holding `bytes` bytes, copied from `data`
// when it is not null; deleted with this object.
class Buffer {
public:
    Buffer(const Functions& gl, GLenum target, std::size_t bytes, const void* data = nullptr,
           GLenum usage = GL_DYNAMIC_COPY);
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&&) = delete;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer();
    GLuint id() const { return id_; }
    std::size_t size() const { return bytes_; }
    // Binds it to an indexed binding point of its target (SSBO binding = N in GLSL).
    void bind_base(GLuint index) const;
    // Copies bytes [offset, offset + bytes) out; throws GlError when out of range.
    void read(void* out, std::size_t bytes, std::size_t offset = 0) const;
    // Copies `bytes` bytes of `data` in at `offset`; throws GlError when out of range.
    void write(const void* data, std::size_t bytes, std::size_t offset = 0) const;

private:
    const Functions* gl_;
    GLenum target_;
    GLuint id_;
    std::size_t bytes_;
};

// The shader-storage buffer in `slot`, made anew when it holds fewer than
// `bytes` bytes (at least 16: a zero-sized one cannot be bound usefully),
// else kept, so passes that run again (a render's clusters) reuse their
// buffers; `data`: its `bytes` bytes copied in.
const Buffer& reserve_storage(const Functions& gl, std::optional<Buffer>& slot, std::size_t bytes,
                              const void* data = nullptr);

// Copies bytes [from_offset, from_offset + bytes) of `from` to `to` at
// `to_offset` on the GPU (glCopyBufferSubData: ordered after the commands
// before it, as a dispatch is; shader writes before it need
// GL_BUFFER_UPDATE_BARRIER_BIT). Throws GlError when out of range.
void copy_buffer(const Functions& gl, const Buffer& from, std::size_t from_offset, const Buffer& to,
                 std::size_t to_offset, std::size_t bytes);

// glDispatchCompute of `groups` work groups of the bound program in rows of
// at most 65,535 (the least GL_MAX_COMPUTE_WORK_GROUP_COUNT a GL 4.3
// context offers): group (x, y) is number y * gl_NumWorkGroups.x + x, and
// the shader skips those past its count.
void dispatch_in_rows(const Functions& gl, std::size_t groups);

}  // namespace blurcull::gl
