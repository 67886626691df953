#include "render/gl/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
// osmesa.h includes GL/gl.h; GL/glcorearb.h (already in) defines the same
// types, and gl.h's own prototypes are never called: everything goes through
// the Functions table.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <utility>

namespace blurcull::gl {

namespace {

using ProcLoader = void (*(*)(const char*))();

// A symbol from a library opened with dlopen, as a function pointer. memcpy
// because ISO C++ has no cast between object and function pointers.
template <class Fn>
Fn library_symbol(void* library, const char* name) {
    void* address = dlsym(library, name);
    Fn fn = nullptr;
    static_assert(sizeof(fn) == sizeof(address), "function and object pointers differ in size");
    if (address != nullptr) std::memcpy(&fn, &address, sizeof(fn));
    return fn;
}

// --- the end of the process --------------------------------------------------
// NVIDIA's EGL registers exit handlers (atexit) while eglInitialize runs, and
// Mesa's EGL does on its first display; they shut the driver down. A GL object
// or context destroyed after them (a static's destructor registered before
// the first eglInitialize runs after them) would call into a dead driver:
// SIGSEGV at exit. So after every eglInitialize (the driver may register
// again each time) and after OSMesa's first context this file registers its
// own handler, which exit runs before those (handlers run in the reverse
// order of registration); from then on every destructor
// here releases nothing (the end of the process frees it all) and
// make_current throws. Contexts and their objects should still be destroyed
// before main returns (gl_context.hpp); this only keeps a straggler from
// crashing the exit.
std::atomic<bool> exit_began{false};

void note_exit() { exit_began.store(true); }

void watch_exit() { std::atexit(note_exit); }

std::once_flag osmesa_exit_watch;
std::atomic<std::size_t> contexts_made_count{0};

// Libraries stay loaded for the process: Mesa registers exit handlers and
// thread-local state that must outlive every context.
void* open_library(const char* name, std::string& error) {
    void* library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
        const char* reason = dlerror();
        error = std::string("cannot open ") + name + ": " + (reason != nullptr ? reason : "unknown reason");
    }
    return library;
}

bool has_extension(const char* list, const char* name) {
    if (list == nullptr) return false;
    std::string_view all(list);
    std::string_view wanted(name);
    std::size_t at = 0;
    while ((at = all.find(wanted, at)) != std::string_view::npos) {
        bool starts = at == 0 || all[at - 1] == ' ';
        std::size_t end = at + wanted.size();
        bool ends = end == all.size() || all[end] == ' ';
        if (starts && ends) return true;
        at = end;
    }
    return false;
}

template <class Fn>
void load_one(Fn& slot, const char* name, void (*(*loader)(const char*))(), std::string& missing) {
    auto proc = loader(name);
    if (proc == nullptr) {
        if (!missing.empty()) missing += ", ";
        missing += name;
        return;
    }
    slot = reinterpret_cast<Fn>(proc);
}

Functions load_functions(void (*(*loader)(const char*))(), const char* loader_name) {
    Functions fns;
    std::string missing;
#define BLURCULL_GL_LOAD(type, name) load_one(fns.name, "gl" #name, loader, missing);
    BLURCULL_GL_FUNCTIONS(BLURCULL_GL_LOAD)
#undef BLURCULL_GL_LOAD
    if (!missing.empty()) throw GlError(std::string(loader_name) + " has no " + missing);
    return fns;
}

const char* gl_string(const Functions& fns, GLenum name) {
    const GLubyte* text = fns.GetString(name);
    return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

void require_gl45(const Functions& fns, ContextKind kind) {
    GLint major = 0;
    GLint minor = 0;
    fns.GetIntegerv(GL_MAJOR_VERSION, &major);
    fns.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 5)) {
        throw GlError(std::string(context_kind_name(kind)) + ": OpenGL 4.5 core needed, got " +
                      gl_string(fns, GL_VERSION));
    }
}

// --- EGL: one surfaceless display for the process ------------------------------
// eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY)
// answers the same display every time, and EGL does not count
// eglInitialize / eglTerminate: one eglTerminate ends the display under every
// context on it. So the display is initialised once and counted here: each
// live context holds it, and the last one to go terminates it (releasing the
// driver's threads and memory when no context is left; the next context
// initialises it again).
struct EglEntryPoints {
    PFNEGLGETPROCADDRESSPROC get_proc = nullptr;
    PFNEGLQUERYSTRINGPROC query_string = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLTERMINATEPROC terminate = nullptr;
    PFNEGLBINDAPIPROC bind_api = nullptr;
    PFNEGLCREATECONTEXTPROC create_context = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroy_context = nullptr;
    PFNEGLMAKECURRENTPROC make_current = nullptr;
    PFNEGLGETCURRENTCONTEXTPROC get_current_context = nullptr;
    PFNEGLGETERRORPROC get_error = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
};

class EglDisplayShare {
public:
    // The process's one; never destroyed (no destructor of it may run at
    // exit, after the driver's handlers).
    static EglDisplayShare& get() {
        static EglDisplayShare* share = new EglDisplayShare;
        return *share;
    }

    // libEGL's entry points, loaded on the first call; throws GlError when
    // libEGL cannot be opened or lacks one.
    const EglEntryPoints& entry_points() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (loaded_) return egl_;
        std::string error;
        void* library = open_library("libEGL.so.1", error);
        if (library == nullptr) throw GlError("EGL: " + error);
        EglEntryPoints e;
        e.get_proc = library_symbol<PFNEGLGETPROCADDRESSPROC>(library, "eglGetProcAddress");
        e.query_string = library_symbol<PFNEGLQUERYSTRINGPROC>(library, "eglQueryString");
        e.initialize = library_symbol<PFNEGLINITIALIZEPROC>(library, "eglInitialize");
        e.terminate = library_symbol<PFNEGLTERMINATEPROC>(library, "eglTerminate");
        e.bind_api = library_symbol<PFNEGLBINDAPIPROC>(library, "eglBindAPI");
        e.create_context = library_symbol<PFNEGLCREATECONTEXTPROC>(library, "eglCreateContext");
        e.destroy_context = library_symbol<PFNEGLDESTROYCONTEXTPROC>(library, "eglDestroyContext");
        e.make_current = library_symbol<PFNEGLMAKECURRENTPROC>(library, "eglMakeCurrent");
        e.get_current_context = library_symbol<PFNEGLGETCURRENTCONTEXTPROC>(library, "eglGetCurrentContext");
        e.get_error = library_symbol<PFNEGLGETERRORPROC>(library, "eglGetError");
        if (!e.get_proc || !e.query_string || !e.initialize || !e.terminate || !e.bind_api || !e.create_context ||
            !e.destroy_context || !e.make_current || !e.get_current_context || !e.get_error)
            throw GlError("EGL: libEGL.so.1 lacks an EGL 1.4 entry point");
        if (!has_extension(e.query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless"))
            throw GlError("EGL: no EGL_MESA_platform_surfaceless (not Mesa's EGL?)");
        e.get_platform_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(e.get_proc("eglGetPlatformDisplayEXT"));
        if (!e.get_platform_display) throw GlError("EGL: no eglGetPlatformDisplayEXT");
        egl_ = e;
        loaded_ = true;
        return egl_;
    }

    // The display, initialised if no live context holds it yet; one more
    // holder. Throws GlError when it cannot be had.
    EGLDisplay acquire() {
        const EglEntryPoints& e = entry_points();
        std::lock_guard<std::mutex> lock(mutex_);
        if (holders_ == 0) {
            EGLDisplay display = e.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (display == EGL_NO_DISPLAY) throw egl_failure(e, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
            EGLint major = 0;
            EGLint minor = 0;
            if (!e.initialize(display, &major, &minor)) throw egl_failure(e, "eglInitialize");
            display_ = display;
            // After the exit handlers eglInitialize may have registered.
            watch_exit();
        }
        ++holders_;
        return display_;
    }

    // One holder fewer; the last terminates the display (not once the
    // process is exiting: the driver may be gone).
    void release() noexcept {
        std::lock_guard<std::mutex> lock(mutex_);
        if (holders_ == 0) return;
        if (--holders_ == 0 && !exit_began.load()) {
            egl_.terminate(display_);
            display_ = EGL_NO_DISPLAY;
        }
    }

    static GlError egl_failure(const EglEntryPoints& e, const char* what) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(e.get_error()));
        return GlError(std::string("EGL: ") + what + " failed (EGL error " + code + ")");
    }

private:
    EglDisplayShare() = default;
    std::mutex mutex_;
    bool loaded_ = false;
    EglEntryPoints egl_;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    int holders_ = 0;  // live contexts on display_
};

}  // namespace

struct HeadlessContext::State {
    ContextKind kind = ContextKind::egl_surfaceless;
    Functions fns;
    // EGL: the shared display, held (acquired) while this is alive.
    const EglEntryPoints* egl = nullptr;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext egl_context = EGL_NO_CONTEXT;
    // OSMesa: its context needs a colour buffer to be made current, even
    // though blurcull renders into FBOs.
    OSMesaContext osmesa_context = nullptr;
    decltype(&OSMesaMakeCurrent) osmesa_make_current = nullptr;
    decltype(&OSMesaDestroyContext) osmesa_destroy_context = nullptr;
    std::vector<std::uint8_t> osmesa_buffer;

    State() = default;
    State(const State&) = delete;
    State& operator=(const State&) = delete;

    ~State() {
        if (exit_began.load()) return;  // the driver may be gone: the process's end frees it all
        if (egl_context != EGL_NO_CONTEXT) {
            // Unbound only when current here: another live context that is
            // current stays current.
            if (egl->get_current_context() == egl_context)
                egl->make_current(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            egl->destroy_context(display, egl_context);
        }
        if (display != EGL_NO_DISPLAY) EglDisplayShare::get().release();
        if (osmesa_context != nullptr) osmesa_destroy_context(osmesa_context);
    }
};

namespace {

std::unique_ptr<HeadlessContext::State> create_egl() {
    EglDisplayShare& share = EglDisplayShare::get();
    const EglEntryPoints& e = share.entry_points();
    auto state = std::make_unique<HeadlessContext::State>();
    state->kind = ContextKind::egl_surfaceless;
    state->egl = &e;
    // From here on the state's destructor releases the display.
    state->display = share.acquire();
    const EGLDisplay display = state->display;
    auto fail = [&](const char* what) { return EglDisplayShare::egl_failure(e, what); };
    const char* display_extensions = e.query_string(display, EGL_EXTENSIONS);
    if (!has_extension(display_extensions, "EGL_KHR_no_config_context") &&
        !has_extension(display_extensions, "EGL_MESA_configless_context"))
        throw GlError("EGL: the surfaceless display has no EGL_KHR_no_config_context");
    if (!has_extension(display_extensions, "EGL_KHR_surfaceless_context"))
        throw GlError("EGL: the surfaceless display has no EGL_KHR_surfaceless_context");
    if (!e.bind_api(EGL_OPENGL_API)) throw fail("eglBindAPI(EGL_OPENGL_API)");
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                 EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    state->egl_context = e.create_context(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (state->egl_context == EGL_NO_CONTEXT) throw fail("eglCreateContext (OpenGL 4.5 core)");
    if (!e.make_current(display, EGL_NO_SURFACE, EGL_NO_SURFACE, state->egl_context))
        throw fail("eglMakeCurrent (surfaceless)");
    state->fns = load_functions(e.get_proc, "eglGetProcAddress");
    require_gl45(state->fns, state->kind);
    return state;
}

std::unique_ptr<HeadlessContext::State> create_osmesa() {
    std::string error;
    void* library = open_library("libOSMesa.so.8", error);
    if (library == nullptr) throw GlError("OSMesa: " + error);
    auto create_context = library_symbol<decltype(&OSMesaCreateContextAttribs)>(library, "OSMesaCreateContextAttribs");
    auto get_proc = library_symbol<decltype(&OSMesaGetProcAddress)>(library, "OSMesaGetProcAddress");
    auto state = std::make_unique<HeadlessContext::State>();
    state->kind = ContextKind::osmesa;
    state->osmesa_make_current = library_symbol<decltype(&OSMesaMakeCurrent)>(library, "OSMesaMakeCurrent");
    state->osmesa_destroy_context = library_symbol<decltype(&OSMesaDestroyContext)>(library, "OSMesaDestroyContext");
    if (!create_context || !get_proc || !state->osmesa_make_current || !state->osmesa_destroy_context)
        throw GlError("OSMesa: libOSMesa.so.8 lacks OSMesaCreateContextAttribs or another entry point");
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                              OSMESA_DEPTH_BITS, 0,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 4,
                              OSMESA_CONTEXT_MINOR_VERSION, 5,
                              0};
    state->osmesa_context = create_context(attributes, nullptr);
    if (state->osmesa_context == nullptr) throw GlError("OSMesa: OSMesaCreateContextAttribs (OpenGL 4.5 core) failed");
    std::call_once(osmesa_exit_watch, watch_exit);  // after any exit handler OSMesa registered
    constexpr int side = 4;
    state->osmesa_buffer.assign(side * side * 4, 0);
    if (!state->osmesa_make_current(state->osmesa_context, state->osmesa_buffer.data(), GL_UNSIGNED_BYTE, side, side))
        throw GlError("OSMesa: OSMesaMakeCurrent failed");
    state->fns = load_functions(get_proc, "OSMesaGetProcAddress");
    require_gl45(state->fns, state->kind);
    return state;
}

}  // namespace

const char* context_kind_name(ContextKind kind) {
    switch (kind) {
        case ContextKind::egl_surfaceless: return "egl";
        case ContextKind::osmesa: return "osmesa";
        case ContextKind::current: return "current";
    }
    return "?";
}

ContextKind parse_context_kind(std::string_view name) {
    if (name == "egl") return ContextKind::egl_surfaceless;
    if (name == "osmesa") return ContextKind::osmesa;
    throw GlError("unknown GL context kind '" + std::string(name) + "' (expected egl or osmesa)");
}

HeadlessContext::HeadlessContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
HeadlessContext::HeadlessContext(HeadlessContext&& other) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&& other) noexcept = default;
HeadlessContext::~HeadlessContext() = default;

HeadlessContext HeadlessContext::create(ContextKind kind) {
    if (kind == ContextKind::current) throw GlError("a current context is wrapped with from_current, not created");
    HeadlessContext made(kind == ContextKind::egl_surfaceless ? create_egl() : create_osmesa());
    const std::size_t count = contexts_made_count.fetch_add(1) + 1;
    // BLURCULL_GL_TRACE_CONTEXTS=1: a line on stderr per context made (the
    // tests count a `blurcull render`'s contexts with it).
    const char* trace = std::getenv("BLURCULL_GL_TRACE_CONTEXTS");
    if (trace != nullptr && *trace != '\0' && std::string_view(trace) != "0") {
        std::fprintf(stderr, "blurcull gl: context %zu made (%s, %s)\n", count, context_kind_name(kind),
                     made.renderer().c_str());
    }
    return made;
}

std::size_t HeadlessContext::contexts_made() { return contexts_made_count.load(); }

bool driver_usable() noexcept { return !exit_began.load(); }

HeadlessContext HeadlessContext::from_current(void (*(*loader)(const char*))(), const char* loader_name) {
    auto state = std::make_unique<State>();
    state->kind = ContextKind::current;
    state->fns = load_functions(loader, loader_name);
    // glGetString answers null without a current context.
    if (state->fns.GetString(GL_VERSION) == nullptr) throw GlError(std::string(loader_name) + ": no current OpenGL context");
    require_gl45(state->fns, state->kind);
    return HeadlessContext(std::move(state));
}

HeadlessContext HeadlessContext::create() {
    const char* forced = std::getenv("BLURCULL_GL_CONTEXT");
    if (forced != nullptr && *forced != '\0') return create(parse_context_kind(forced));
    try {
        return create(ContextKind::egl_surfaceless);
    } catch (const GlError& egl_error) {
        try {
            return create(ContextKind::osmesa);
        } catch (const GlError& osmesa_error) {
            throw GlError(std::string("no headless OpenGL 4.5 context: ") + egl_error.what() + "; " +
                          osmesa_error.what());
        }
    }
}

const Functions& HeadlessContext::gl() const { return state_->fns; }
ContextKind HeadlessContext::kind() const { return state_->kind; }
std::string HeadlessContext::renderer() const { return gl_string(state_->fns, GL_RENDERER); }
std::string HeadlessContext::version() const { return gl_string(state_->fns, GL_VERSION); }

bool HeadlessContext::software() const {
    const std::string name = renderer();
    for (const char* software : {"llvmpipe", "softpipe", "swrast"}) {
        if (name.find(software) != std::string::npos) return true;
    }
    return false;
}

void HeadlessContext::make_current() const {
    const State& s = *state_;
    if (s.kind == ContextKind::current) return;  // the caller's to keep current
    if (exit_began.load()) throw GlError("GL: the process is exiting (the driver may have shut down)");
    if (s.kind == ContextKind::egl_surfaceless) {
        if (!s.egl->make_current(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.egl_context))
            throw GlError("EGL: eglMakeCurrent failed");
    } else {
        auto* buffer = const_cast<std::uint8_t*>(s.osmesa_buffer.data());
        if (!s.osmesa_make_current(s.osmesa_context, buffer, GL_UNSIGNED_BYTE, 4, 4))
            throw GlError("OSMesa: OSMesaMakeCurrent failed");
    }
}

void HeadlessContext::make_current_for_release() const noexcept {
    if (!driver_usable()) return;
    try {
        make_current();
    } catch (const GlError&) {
        // Nothing better to do in a destructor: the objects go with whatever is current.
    }
}

void check_gl(const Functions& gl, const char* what) {
    GLenum code = gl.GetError();
    if (code == GL_NO_ERROR) return;
    char text[16];
    std::snprintf(text, sizeof text, "0x%04x", static_cast<unsigned>(code));
    throw GlError(std::string(what) + ": GL error " + text);
}

namespace {

std::string shader_log(const Functions& gl, GLuint shader) {
    GLint length = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return log.c_str();
}

std::string program_log(const Functions& gl, GLuint program) {
    GLint length = 0;
    gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return log.c_str();
}

}  // namespace

Program::Program(const Functions& gl, const std::vector<ShaderStage>& stages) : gl_(&gl), id_(gl.CreateProgram()) {
    if (id_ == 0) throw GlError("glCreateProgram failed");
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint shader : shaders) {
            gl.DetachShader(id_, shader);
            gl.DeleteShader(shader);
        }
    };
    try {
        for (const ShaderStage& stage : stages) {
            GLuint shader = gl.CreateShader(stage.type);
            if (shader == 0) throw GlError("glCreateShader failed");
            shaders.push_back(shader);
            std::vector<const GLchar*> texts;
            std::vector<GLint> lengths;
            for (std::string_view part : stage.sources) {
                texts.push_back(part.data());
                lengths.push_back(static_cast<GLint>(part.size()));
            }
            gl.ShaderSource(shader, static_cast<GLsizei>(texts.size()), texts.data(), lengths.data());
            gl.CompileShader(shader);
            GLint ok = GL_FALSE;
            gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
            if (ok != GL_TRUE) throw GlError("shader compilation failed: " + shader_log(gl, shader));
            gl.AttachShader(id_, shader);
        }
        gl.LinkProgram(id_);
        GLint ok = GL_FALSE;
        gl.GetProgramiv(id_, GL_LINK_STATUS, &ok);
        if (ok != GL_TRUE) throw GlError("program link failed: " + program_log(gl, id_));
    } catch (...) {
        cleanup();
        gl.DeleteProgram(id_);
        throw;
    }
    cleanup();
}

Program::Program(Program&& other) noexcept : gl_(other.gl_), id_(std::exchange(other.id_, 0u)) {}

Program::~Program() {
    if (id_ != 0 && driver_usable()) gl_->DeleteProgram(id_);
}

Texture::Texture(const Functions& gl, GLenum target, GLenum format, int width, int height, int samples)
    : gl_(&gl), target_(target) {
    gl.GenTextures(1, &id_);
    gl.BindTexture(target, id_);
    if (target == GL_TEXTURE_2D_MULTISAMPLE) {
        gl.TexStorage2DMultisample(target, samples, format, width, height, GL_TRUE);
    } else {
        gl.TexStorage2D(target, 1, format, width, height);
    }
    gl.BindTexture(target, 0);
    check_gl(gl, "texture storage");
}

Texture::~Texture() {
    if (driver_usable()) gl_->DeleteTextures(1, &id_);
}

Framebuffer::Framebuffer(const Functions& gl) : gl_(&gl) { gl.GenFramebuffers(1, &id_); }

Framebuffer::~Framebuffer() {
    if (driver_usable()) gl_->DeleteFramebuffers(1, &id_);
}

VertexArray::VertexArray(const Functions& gl) : gl_(&gl) { gl.GenVertexArrays(1, &id_); }

VertexArray::VertexArray(VertexArray&& other) noexcept : gl_(other.gl_), id_(std::exchange(other.id_, 0u)) {}

VertexArray::~VertexArray() {
    if (id_ != 0 && driver_usable()) gl_->DeleteVertexArrays(1, &id_);
}

Buffer::Buffer(const Functions& gl, GLenum target, std::size_t bytes, const void* data, GLenum usage)
    : gl_(&gl), target_(target), id_(0), bytes_(bytes) {
    gl.GenBuffers(1, &id_);
    gl.BindBuffer(target, id_);
    gl.BufferData(target, static_cast<GLsizeiptr>(bytes), data, usage);
    gl.BindBuffer(target, 0);
    check_gl(gl, "creating a buffer");
}

Buffer::Buffer(Buffer&& other) noexcept
    : gl_(other.gl_), target_(other.target_), id_(std::exchange(other.id_, 0u)), bytes_(other.bytes_) {}

Buffer::~Buffer() {
    if (id_ != 0 && driver_usable()) gl_->DeleteBuffers(1, &id_);
}

void Buffer::bind_base(GLuint index) const { gl_->BindBufferBase(target_, index, id_); }

void Buffer::read(void* out, std::size_t bytes, std::size_t offset) const {
    if (offset > bytes_ || bytes > bytes_ - offset) throw GlError("reading past the end of a buffer");
    gl_->BindBuffer(target_, id_);
    gl_->GetBufferSubData(target_, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
    gl_->BindBuffer(target_, 0);
    check_gl(*gl_, "reading a buffer");
}

void Buffer::write(const void* data, std::size_t bytes, std::size_t offset) const {
    if (offset > bytes_ || bytes > bytes_ - offset) throw GlError("writing past the end of a buffer");
    gl_->BindBuffer(target_, id_);
    gl_->BufferSubData(target_, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
    gl_->BindBuffer(target_, 0);
}

const Buffer& reserve_storage(const Functions& gl, std::optional<Buffer>& slot, std::size_t bytes, const void* data) {
    if (!slot || slot->size() < bytes) {
        slot.reset();
        slot.emplace(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(bytes, 16));
    }
    if (data != nullptr && bytes > 0) slot->write(data, bytes);
    return *slot;
}

void copy_buffer(const Functions& gl, const Buffer& from, std::size_t from_offset, const Buffer& to,
                 std::size_t to_offset, std::size_t bytes) {
    if (bytes == 0) return;
    if (from_offset > from.size() || bytes > from.size() - from_offset || to_offset > to.size() ||
        bytes > to.size() - to_offset)
        throw GlError("gl: a buffer copy of " + std::to_string(bytes) + " bytes out of range");
    gl.BindBuffer(GL_COPY_READ_BUFFER, from.id());
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, to.id());
    gl.CopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(from_offset),
                         static_cast<GLintptr>(to_offset), static_cast<GLsizeiptr>(bytes));
    gl.BindBuffer(GL_COPY_READ_BUFFER, 0);
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void dispatch_in_rows(const Functions& gl, std::size_t groups) {
    constexpr std::size_t row = 65535;
    gl.DispatchCompute(static_cast<GLuint>(std::min(groups, row)), static_cast<GLuint>((groups + row - 1) / row), 1);
}

}  // namespace blurcull::gl
