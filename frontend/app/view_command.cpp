#include "app/view_command.hpp"

#include "app/gl_dof_secondary.hpp"
#include "app/scene_setup.hpp"
#include "app/text_overlay.hpp"
#include "app/view_progressive.hpp"

#include "render/common/image.hpp"
#include "render/common/motion_segments.hpp"
#include "render/common/render_types.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "scene/motion_segments.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include <dlfcn.h>
#include <link.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {

const char* const view_controls_help =
    "Controls: left drag orbit | wheel dolly | R reset view\n"
    "  A / Shift+A  lens radius x1.25 / /1.25     F / Shift+F  focus distance x1.1 / /1.1\n"
    "  S / Shift+S  shutter length x1.25 / /1.25  B / Shift+B  blur scale x1.25 / /1.25\n"
    "  N  next spp (4, 8, 16, 32)                 C  next cull method (bbox, hull, dualspace, twostage)\n"
    "  M  method stochastic <-> dof-secondary (mirrors and glass: one bounce, seconds a frame on llvmpipe)\n"
    "  P  screenshot (--screenshot FILE, else view-N.png)   Esc / Q  quit\n";

namespace {

// --method dof-secondary's size when --size is not given: on a quiet machine
// its frame of mirror-sphere took 11.8 s on llvmpipe at 320x240 and 33.6 s at
// 480x360, nearly all of it the primary pass (docs/secondary-rays.md, "In
// the window").
const char* const view_dof_secondary_size = "320x240";

using Clock = std::chrono::steady_clock;

constexpr int spp_steps[] = {4, 8, 16, 32};
constexpr CullMethod cull_steps[] = {CullMethod::bbox, CullMethod::hull, CullMethod::dualspace, CullMethod::two_stage};

int next_spp(int spp) {
    for (int step : spp_steps) {
        if (step > spp) return step;
    }
    return spp_steps[0];
}

CullMethod next_cull(CullMethod cull) {
    for (std::size_t i = 0; i < std::size(cull_steps); ++i) {
        if (cull_steps[i] == cull) return cull_steps[(i + 1) % std::size(cull_steps)];
    }
    return cull_steps[0];
}

void require_writable_folder(const std::string& path, const char* flag) {
    std::size_t slash = path.find_last_of('/');
    std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
    if (access(folder.c_str(), W_OK) != 0) {
        throw std::runtime_error(std::string(flag) + ": cannot write '" + path + "': folder '" + folder +
                                 "' is not writable");
    }
}

// GLFW reports errors through a callback; the last one goes into messages.
std::string& last_glfw_error() {
    static std::string error;
    return error;
}

void record_glfw_error(int code, const char* description) {
    char text[32];
    std::snprintf(text, sizeof text, "GLFW error 0x%05x: ", code);
    last_glfw_error() = text + std::string(description != nullptr ? description : "unknown");
}

// glfwInit/glfwTerminate and the window, released in order on any exit.
struct GlfwSession {
    GLFWwindow* window = nullptr;
    GlfwSession() {
        glfwSetErrorCallback(record_glfw_error);
        const char* display = std::getenv("DISPLAY");
        const char* wayland = std::getenv("WAYLAND_DISPLAY");
        if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0')) {
            throw std::runtime_error("no display: set DISPLAY or run under xvfb-run");
        }
        if (glfwInit() != GLFW_TRUE) {
            throw std::runtime_error("cannot open the display '" + std::string(display != nullptr ? display : "") +
                                     "' (" + last_glfw_error() + "); set DISPLAY or run under xvfb-run");
        }
    }
    GlfwSession(const GlfwSession&) = delete;
    GlfwSession& operator=(const GlfwSession&) = delete;
    ~GlfwSession() {
        if (window != nullptr) glfwDestroyWindow(window);
        glfwTerminate();
    }
};

// Keeps every library loaded now (libGL, Mesa's GLX and DRI driver, LLVM)
// loaded until the process exits, like gl_context does for EGL and OSMesa:
// glfwTerminate would dlclose them, and Mesa's exit handlers and
// LeakSanitizer's reports need their code still mapped.
void pin_loaded_libraries() {
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void*) {
            if (info->dlpi_name != nullptr && info->dlpi_name[0] == '/') {
                dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            }
            return 0;
        },
        nullptr);
}

// What the user changes; the scene is re-made from it when blur scale or
// shutter change, the camera is re-posed from it on every frame.
struct ViewState {
    float yaw = 0.0f;    // radians, about the view's up axis through the scene centre
    float pitch = 0.0f;  // radians, about the view's right axis
    float dolly = 0.0f;  // view units moved towards the centre
    float lens_radius = 0.0f;
    float focus = 1.0f;
    float shutter_open = 0.0f;
    float shutter_close = 1.0f;
    double blur_scale = 1.0;
    int spp = 4;
    CullMethod cull = CullMethod::bbox;
    RenderMethod method = RenderMethod::stochastic;
};

// M: the view's two methods, the directly seen image and the bounce.
RenderMethod other_method(RenderMethod method) {
    return method == RenderMethod::dof_secondary ? RenderMethod::stochastic : RenderMethod::dof_secondary;
}

// The orbit: rotates the world about its centre in view space, then moves
// the camera along its axis; the same for shutter open and close, so camera
// motion stays what the scene says.
glm::mat4 orbit_transform(const ViewState& view, glm::vec3 centre_in_view) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, view.dolly));
    m = glm::translate(m, centre_in_view);
    m = glm::rotate(m, view.pitch, glm::vec3(1.0f, 0.0f, 0.0f));
    m = glm::rotate(m, view.yaw, glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::translate(m, -centre_in_view);
}

glm::vec3 scene_centre(const Scene& scene) {
    if (scene.position_open.empty()) return glm::vec3(0.0f);
    glm::vec3 low = scene.position_open.front(), high = low;
    for (const glm::vec3& p : scene.position_open) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    return 0.5f * (low + high);
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, a, b, c, d);
    return text;
}

// --backend for the window: gl or cpu as named; auto draws with the cpu
// backend when the window's GL is software (llvmpipe is far slower than the
// cpu backend on the same cores) and the method is stochastic (the one the
// cpu view refines progressively), else with gl.
bool view_draws_with_cpu(const std::string& backend, bool software_gl, RenderMethod method) {
    return backend == "cpu" || (backend == "auto" && software_gl && method == RenderMethod::stochastic);
}

// The GL options of a frame: on a hardware GPU the stochastic method, and
// dof-secondary's primary pass, on the compute pipeline (what render
// --backend auto picks there: docs/gl-backend.md, "The compute pipeline");
// on software GL, and for the other methods, the fragment pipeline.
GlOptions view_gl_options(bool software_gl, RenderMethod method) {
    GlOptions options;
    if (!software_gl && (method == RenderMethod::stochastic || method == RenderMethod::dof_secondary))
        options.pipeline = GlPipeline::compute;
    return options;
}

// The window's image: the render plus the overlay, as an RGBA8 texture in an
// FBO that is blitted (flipped: row 0 of the image is its top) to the window.
class Presenter {
public:
    Presenter(const gl::Functions& functions, int width, int height)
        : gl_(&functions), width_(width), height_(height), texture_(functions, GL_TEXTURE_2D, GL_RGBA8, width, height),
          framebuffer_(functions) {
        gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
        gl_->FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_.id(), 0);
        const GLenum status = gl_->CheckFramebufferStatus(GL_READ_FRAMEBUFFER);
        gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        if (status != GL_FRAMEBUFFER_COMPLETE) throw gl::GlError("view: the display framebuffer is incomplete");
        gl::check_gl(*gl_, "view: display texture");
    }
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    void show(const Image& image, int window_width, int window_height) {
        std::vector<unsigned char> bytes(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int channel = 0; channel < 3; ++channel) {
                const float encoded = linear_to_srgb(image.pixels[i][channel]);
                bytes[4 * i + static_cast<std::size_t>(channel)] =
                    static_cast<unsigned char>(std::lround(encoded * 255.0f));
            }
            bytes[4 * i + 3] = 255;
        }
        gl_->BindTexture(GL_TEXTURE_2D, texture_.id());
        gl_->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        gl_->BindTexture(GL_TEXTURE_2D, 0);
        gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
        gl_->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        gl_->Viewport(0, 0, window_width, window_height);
        const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        gl_->ClearBufferfv(GL_COLOR, 0, black);
        gl_->BlitFramebuffer(0, 0, width_, height_, 0, window_height, window_width, 0, GL_COLOR_BUFFER_BIT,
                             window_width == width_ && window_height == height_ ? GL_NEAREST : GL_LINEAR);
        gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        gl::check_gl(*gl_, "view: presenting the frame");
    }

private:
    const gl::Functions* gl_;
    int width_, height_;
    gl::Texture texture_;
    gl::Framebuffer framebuffer_;
};

// The window's back buffer (what the last show() drew) as a PNG.
void write_window_png(const gl::Functions& gl, int width, int height, const std::string& path) {
    std::vector<unsigned char> bytes(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    gl::check_gl(gl, "view: reading the window");
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            // GL's row 0 is the bottom.
            const std::size_t at = (static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) +
                                    static_cast<std::size_t>(x)) * 4;
            image.at(x, y) = glm::vec3(srgb_to_linear(bytes[at] / 255.0f), srgb_to_linear(bytes[at + 1] / 255.0f),
                                       srgb_to_linear(bytes[at + 2] / 255.0f));
        }
    }
    write_png(path, image);
}

// Input collected by the GLFW callbacks between frames.
struct Input {
    ViewState* view = nullptr;
    bool dragging = false;
    double last_x = 0.0, last_y = 0.0;
    float dolly_step = 1.0f;
    bool changed = false;         // re-render
    bool scene_changed = false;   // re-make the scene (blur scale, shutter)
    bool screenshot = false;
    bool reset = false;
};

Input& input_of(GLFWwindow* window) { return *static_cast<Input*>(glfwGetWindowUserPointer(window)); }

void on_key(GLFWwindow* window, int key, int, int action, int mods) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    Input& input = input_of(window);
    ViewState& view = *input.view;
    const bool down = (mods & GLFW_MOD_SHIFT) != 0;
    const float factor = down ? 0.8f : 1.25f;
    switch (key) {
        case GLFW_KEY_ESCAPE:
        case GLFW_KEY_Q: glfwSetWindowShouldClose(window, GLFW_TRUE); return;
        case GLFW_KEY_A:
            // From a pinhole, A opens a small aperture: 1% of the focus distance.
            view.lens_radius = view.lens_radius > 0.0f ? view.lens_radius * factor : (down ? 0.0f : 0.01f * view.focus);
            break;
        case GLFW_KEY_F: view.focus *= down ? 1.0f / 1.1f : 1.1f; break;
        case GLFW_KEY_S:
            view.shutter_close = view.shutter_open + (view.shutter_close - view.shutter_open) * factor;
            input.scene_changed = true;
            break;
        case GLFW_KEY_B:
            view.lens_radius *= factor;
            view.blur_scale *= static_cast<double>(factor);
            input.scene_changed = true;
            break;
        case GLFW_KEY_N: view.spp = next_spp(view.spp); break;
        case GLFW_KEY_C: view.cull = next_cull(view.cull); break;
        case GLFW_KEY_M: view.method = other_method(view.method); break;
        case GLFW_KEY_R: input.reset = true; break;
        case GLFW_KEY_P: input.screenshot = true; return;
        default: return;
    }
    input.changed = true;
}

void on_mouse_button(GLFWwindow* window, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    Input& input = input_of(window);
    input.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(window, &input.last_x, &input.last_y);
}

void on_cursor(GLFWwindow* window, double x, double y) {
    Input& input = input_of(window);
    if (!input.dragging) return;
    // Half a turn across the window's width.
    int width = 1, height = 1;
    glfwGetWindowSize(window, &width, &height);
    const float per_pixel = 3.14159265f / static_cast<float>(std::max(width, 1));
    input.view->yaw += static_cast<float>(x - input.last_x) * per_pixel;
    input.view->pitch = std::clamp(input.view->pitch + static_cast<float>(y - input.last_y) * per_pixel, -1.5f, 1.5f);
    input.last_x = x;
    input.last_y = y;
    input.changed = true;
}

void on_scroll(GLFWwindow* window, double, double y_offset) {
    Input& input = input_of(window);
    input.view->dolly += static_cast<float>(y_offset) * input.dolly_step;
    input.changed = true;
}

// The scene request of the view: the command's flags, with the shutter always
// explicit (the view changes it) and the loaders' defaults when not given.
SceneRequest view_scene_request(const ViewCommand& command, int width, int height) {
    SceneRequest request;
    request.scene = command.scene;
    request.aspect = static_cast<float>(width) / static_cast<float>(height);
    request.blur_scale = command.blur_scale;
    request.has_shutter = true;
    request.shutter_open = 0.0f;
    request.shutter_close = is_gltf_file(command.scene) ? 1.0f / 24.0f : 1.0f;
    if (!command.shutter.empty()) parse_shutter(command.shutter, request.shutter_open, request.shutter_close);
    request.lens_radius = command.lens_radius;
    request.fstop = command.fstop;
    request.focus = command.focus;
    request.motion_segments = parse_motion_segments(command.motion_segments);
    request.blend_opaque = command.alpha_blend == "opaque";
    request.image_height = height;
    return request;
}

// A width x height OpenGL 4.5 core window, not resizable, current, no vsync.
GLFWwindow* open_window(int width, int height) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, 0);
    GLFWwindow* window = glfwCreateWindow(width, height, "blurcull view", nullptr, nullptr);
    if (window == nullptr) {
        throw std::runtime_error("cannot open an OpenGL 4.5 core window (" + last_glfw_error() + ")");
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
    pin_loaded_libraries();  // the context's creation loaded the DRI driver
    return window;
}

// One `blurcull view` run: the window, the renderer on its context, what the
// user changed, and the loop that re-renders when something did. About 350
// lines, over the project's ~250 by choice: the pieces with a job of their
// own are out already (input callbacks above, the progressive worker in
// view_progressive.hpp, text in text_overlay.cpp, the presenter); what is
// left is one loop's steps over one window's state, which split classes
// would only pass back and forth.
class ViewSession {
public:
    ViewSession(const ViewCommand& command, int width, int height)
        : command_(command),
          secondary_(command.secondary_options()),
          width_(width),
          height_(height),
          request_(view_scene_request(command, width, height)),
          base_(load_scene(request_)),
          view_(initial_view(command, base_, request_)),
          initial_(view_),
          window_((glfw_.window = open_window(width, height))),
          // The renderer (gl) is made in the body, on a copy of this table.
          window_context_(gl::HeadlessContext::from_current(glfwGetProcAddress, "glfwGetProcAddress")),
          timing_label_(window_context_.software() ? "llvmpipe, software" : "GPU"),
          presenter_(window_context_.gl(), width, height),
          scene_name_(stem(command.scene)),  // a glTF path without its folders
          centre_(scene_centre(base_)) {
        input_.view = &view_;
        glfwSetWindowUserPointer(window_, &input_);
        glfwSetKeyCallback(window_, on_key);
        glfwSetMouseButtonCallback(window_, on_mouse_button);
        glfwSetCursorPosCallback(window_, on_cursor);
        glfwSetScrollCallback(window_, on_scroll);
        cpu_ = view_draws_with_cpu(command.backend, window_context_.software(), view_.method);
        if (cpu_) {
            // "llvmpipe (LLVM 15.0.6, 256 bits)": its first word is the name.
            const std::string gl = window_context_.renderer().substr(0, window_context_.renderer().find(' '));
            timing_label_ = "cpu backend; GL " + gl + (window_context_.software() ? ", software" : "");
            progressive_ = std::make_unique<ProgressiveView>([] { glfwPostEmptyEvent(); });
        } else {
            renderer_.emplace(gl::HeadlessContext::from_current(glfwGetProcAddress, "glfwGetProcAddress"));
            // gl draws one linear motion per triangle: auto's segments (the
            // default) become the chords, warned, as in `render --backend gl`.
            if (base_.motion_segments_auto && scene_motion_segments(base_) > 1) {
                const int dropped = drop_motion_segments(base_);
                std::fprintf(stderr, "warning: %s\n", dropped_motion_segments_warning("gl", dropped).c_str());
            }
        }
    }

    void run() {
        if (!command_.quiet) {
            std::fprintf(stderr, "blurcull view: %s on %s\n%s", command_.scene.c_str(),
                         cpu_ ? timing_label_.c_str() : renderer_->description().c_str(), view_controls_help);
        }
        if (cpu_) {
            run_progressive();
            return;
        }
        warm_up();
        while (!glfwWindowShouldClose(window_)) {
            if (command_.frames > 0 && rendered_ == command_.frames) break;
            wait_for_change();
            apply_input();
            int window_width = width_, window_height = height_;
            glfwGetFramebufferSize(window_, &window_width, &window_height);
            if (needs_render_) render_frame(window_width, window_height);
            take_screenshots(window_width, window_height);
            glfwSwapBuffers(window_);
        }
    }

private:
    static ViewState initial_view(const ViewCommand& command, const Scene& base, const SceneRequest& request) {
        ViewState view;
        view.lens_radius = base.camera.lens_radius;
        view.focus = base.camera.focus_distance;
        view.shutter_open = request.shutter_open;
        view.shutter_close = request.shutter_close;
        view.blur_scale = command.blur_scale;
        view.spp = command.spp;
        view.cull = parse_cull_method(command.cull);
        view.method = parse_render_method(command.method);
        return view;
    }

    // llvmpipe compiles a program's code on its first draw: a 1x1 frame
    // first, as render_gl does, so frame times are frames alone.
    // With dof-secondary it goes through that method, so a scene it refuses
    // (motion segments) is refused here with its message, as render does.
    void warm_up() {
        glfwSetWindowTitle(window_, "blurcull view: compiling shaders...");
        glfwPollEvents();
        RenderSettings settings;
        settings.width = 1;
        settings.height = 1;
        settings.spp = 4;
        settings.progress = false;
        render_with_method(base_, settings, view_.method);
    }

    // One frame of `method` on the window's context: GlRenderer::render, or
    // for dof-secondary the same GL passes as `render --backend gl` (the
    // trace pass compiled on first use). Motion segments (K > 1) are refused
    // with render's lines: render_gl's check (GlRenderer::render has none)
    // and render_dof_secondary's own.
    RenderResult render_with_method(const Scene& scene, RenderSettings settings, RenderMethod method) {
        settings.method = method;
        const GlOptions options = view_gl_options(window_context_.software(), method);
        if (method != RenderMethod::dof_secondary) {
            refuse_motion_segments(scene, "gl");
            return renderer_->render(scene, settings, options);
        }
        if (!dof_secondary_) dof_secondary_.emplace(*renderer_, window_context_);
        return dof_secondary_->render(scene, settings, options, secondary_);
    }

    // --frames: between frames a turn of the orbit and the next cull method,
    // so both the per-triangle (bbox, hull) and per-cell (dualspace,
    // twostage) bounds run. Interactive: sleeps until something happens,
    // then takes every queued event before rendering once.
    void wait_for_change() {
        if (command_.frames > 0) {
            if (rendered_ > 0) {
                view_.yaw += 0.35f;
                view_.cull = next_cull(view_.cull);
                needs_render_ = true;
            }
            return;
        }
        if (!needs_render_) glfwWaitEvents();
        glfwPollEvents();
    }

    void apply_input() {
        if (input_.reset) {
            view_ = initial_;
            input_.reset = false;
            input_.scene_changed = true;
        }
        if (input_.scene_changed) {
            request_.blur_scale = view_.blur_scale;
            request_.shutter_open = view_.shutter_open;
            request_.shutter_close = view_.shutter_close;
            request_.lens_radius = -1.0;
            request_.fstop = -1.0;
            base_ = load_scene(request_);
            input_.scene_changed = false;
        }
        needs_render_ = needs_render_ || input_.changed;
        input_.changed = false;
    }

    // The scene with the view's camera: orbit, lens and focus.
    Scene posed_scene() {
        Scene posed = base_;
        const glm::vec3 centre_in_view = glm::vec3(base_.camera.view_open * glm::vec4(centre_, 1.0f));
        input_.dolly_step = 0.1f * std::max(glm::length(centre_in_view), 1e-3f);
        const glm::mat4 orbit = orbit_transform(view_, centre_in_view);
        posed.camera.view_open = orbit * base_.camera.view_open;
        posed.camera.view_close = orbit * base_.camera.view_close;
        posed.camera.lens_radius = view_.lens_radius;
        posed.camera.focus_distance = view_.focus;
        posed.validated = false;  // camera from the keys: the renderer checks it again
        return posed;
    }

    // The settings of a frame: the view's spp and cull, the command's seed.
    RenderSettings frame_settings() const {
        RenderSettings settings;
        settings.width = width_;
        settings.height = height_;
        settings.spp = view_.spp;
        settings.seed = command_.seed;
        settings.cull = view_.cull;
        settings.progress = false;
        return settings;
    }

    void render_frame(int window_width, int window_height) {
        const RenderSettings settings = frame_settings();
        const bool bounce = view_.method == RenderMethod::dof_secondary;
        const std::string busy = "blurcull view: rendering " + std::to_string(view_.spp) + " spp" +
                                 (bounce ? ", dof-secondary: primary pass, then the bounces..." : "...");
        glfwSetWindowTitle(window_, busy.c_str());
        glfwPollEvents();
        const Clock::time_point start = Clock::now();
        std::optional<RenderResult> rendered = render_or_keep_method(settings);
        if (!rendered) return;
        RenderResult& result = *rendered;
        const double frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        const RenderStats& stats = result.stats;
        draw_text_panel(result.image, 6, 6,
                        overlay_text(stats, std::to_string(view_.spp) + " spp",
                                     format("frame %.0f ms", frame_ms) + " (" + timing_label_ + ")"),
                        width_ >= 640 ? 2 : 1);
        shown_ = std::move(result.image);
        presenter_.show(shown_, window_width, window_height);
        const std::string title = "blurcull view: " + scene_name_ + " | " + (bounce ? "dof-secondary, " : "") +
                                  to_string(view_.cull) + " " + std::to_string(view_.spp) + " spp | " +
                                  format("STE %.2f%%", 100.0 * stats.ste()) + " | " + format("%.0f ms", frame_ms) +
                                  " " + timing_label_;
        glfwSetWindowTitle(window_, title.c_str());
        ++rendered_;
        needs_render_ = false;
        if (command_.frames > 0 && !command_.quiet) {
            std::printf("frame %d: method %s, cull %s, %d spp, STE %.4f, %.1f ms (%s)\n", rendered_,
                        to_string(view_.method), to_string(view_.cull), view_.spp, stats.ste(), frame_ms,
                        timing_label_.c_str());
            std::fflush(stdout);
        }
    }

    // The frame in the view's method. A method the scene cannot take,
    // switched to with M, is switched back with one warning line (the
    // method given on the command line was refused by warm_up already).
    std::optional<RenderResult> render_or_keep_method(const RenderSettings& settings) {
        try {
            RenderResult result = render_with_method(posed_scene(), settings, view_.method);
            for (const std::string& warning : result.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
            return result;
        } catch (const std::invalid_argument& error) {
            if (view_.method == initial_.method) throw;
            std::fprintf(stderr, "warning: %s; back to method %s\n", error.what(),
                         to_string(other_method(view_.method)));
            view_.method = other_method(view_.method);
            needs_render_ = true;  // the next turn of the loop renders the method back
            return std::nullopt;
        }
    }

    // The cpu backend's loop: a change submits a job to the worker, which
    // wakes the loop with each pass it finishes; --frames N: N views along
    // the orbit (as the gl loop's), each refined to the target spp, one line
    // per pass.
    void run_progressive() {
        std::uint64_t job = 0;
        while (!glfwWindowShouldClose(window_)) {
            if (command_.frames > 0 && rendered_ == command_.frames) break;
            if (needs_render_) {
                job = progressive_->submit(posed_scene(), frame_settings());
                needs_render_ = false;
            }
            glfwWaitEvents();  // input, or the worker's wake
            keep_stochastic_method();
            apply_input();
            std::optional<ViewFrame> frame = progressive_->take();
            if (!frame && !input_.screenshot) continue;
            int window_width = width_, window_height = height_;
            glfwGetFramebufferSize(window_, &window_width, &window_height);
            if (frame) {
                show_pass(*frame, window_width, window_height);
                if (frame->job == job && frame->converged()) ++rendered_;
                if (command_.frames > 0 && frame->job == job && frame->converged() && rendered_ < command_.frames) {
                    view_.yaw += 0.35f;
                    view_.cull = next_cull(view_.cull);
                    needs_render_ = true;
                }
            }
            take_screenshots(window_width, window_height);
            glfwSwapBuffers(window_);
        }
    }

    // M on the cpu backend: dof-secondary is drawn by the gl backend only.
    void keep_stochastic_method() {
        if (view_.method == RenderMethod::stochastic) return;
        view_.method = RenderMethod::stochastic;
        std::fprintf(stderr, "warning: the cpu backend's view draws --method stochastic only; for dof-secondary "
                             "run with --backend gl\n");
    }

    // One image from the worker, with the overlay: spp so far / target, the
    // pass time, the backend.
    void show_pass(ViewFrame& frame, int window_width, int window_height) {
        for (const std::string& warning : frame.warnings) {
            if (!command_.quiet && warned_.insert(warning).second) std::fprintf(stderr, "warning: %s\n", warning.c_str());
        }
        const std::string preview = frame.preview_scale > 1 ? " (preview 1/" + std::to_string(frame.preview_scale) +
                                                                  ", " + to_string(frame.cull) + ")"
                                                            : "";
        const std::string spp_text = std::to_string(frame.samples) + "/" + std::to_string(frame.target) + " spp" + preview;
        const std::string time_text = format("pass %.0f ms", frame.pass_ms) + " (" + timing_label_ + ")";
        draw_text_panel(frame.image, 6, 6, overlay_text(frame.stats, spp_text, time_text), width_ >= 640 ? 2 : 1);
        shown_ = std::move(frame.image);
        presenter_.show(shown_, window_width, window_height);
        const std::string title = "blurcull view: " + scene_name_ + " | " + to_string(view_.cull) + " " + spp_text +
                                  " | " + format("STE %.2f%%", 100.0 * frame.stats.ste()) + " | " +
                                  format("pass %.0f ms", frame.pass_ms) + " cpu backend";
        glfwSetWindowTitle(window_, title.c_str());
        if (command_.frames > 0 && !command_.quiet) {
            std::printf("frame %d pass %d: cull %s, %s, STE %.4f, %.1f ms, %.1f ms CPU (%s)\n", rendered_ + 1,
                        frame.pass, to_string(view_.cull), spp_text.c_str(), frame.stats.ste(), frame.pass_ms,
                        frame.pass_cpu_ms, timing_label_.c_str());
            std::fflush(stdout);
        }
    }

    // The overlay: settings (with `spp_text`), camera, STE, `time_line`;
    // with dof-secondary a fifth line, bounce_line.
    std::string overlay_text(const RenderStats& stats, const std::string& spp_text, const std::string& time_line) const {
        const std::string settings_line = scene_name_ + "  " + std::to_string(width_) + "x" +
                                          std::to_string(height_) + "  " + spp_text + "  cull " +
                                          to_string(view_.cull);
        const std::string camera_line = format("lens %.4g  focus %.4g  shutter [%.3g, %.3g]", view_.lens_radius,
                                               view_.focus, view_.shutter_open, view_.shutter_close) +
                                        format("  blur x%.3g", view_.blur_scale);
        const std::string ste_line = format("STE %.2f%%  (%.0f hit / %.0f tested)", 100.0 * stats.ste(),
                                            static_cast<double>(stats.samples_hit),
                                            static_cast<double>(stats.samples_tested));
        const std::string text = settings_line + "\n" + camera_line + "\n" + ste_line + "\n" + time_line;
        return view_.method == RenderMethod::dof_secondary ? text + "\n" + bounce_line(stats) : text;
    }

    // dof-secondary's fifth line: the method, its bounced rays, clusters, the host's
    // share of the frame (resolve + bounce: clusters, layers, traces) and
    // the layers per cluster view x their texels.
    std::string bounce_line(const RenderStats& stats) const {
        double clusters = 0.0, bounce_ms = 0.0;
        for (const auto& [name, value] : stats.counters) {
            if (name == "clusters") clusters = value;
        }
        for (const auto& [name, ms] : stats.ms_per_phase) {
            if (name == "resolve" || name == "bounce") bounce_ms += ms;
        }
        return format("dof-secondary %.0f rays %.0f clusters %.0f ms", static_cast<double>(stats.secondary_rays),
                      clusters, bounce_ms) +
               " " + std::to_string(secondary_.layers) + "x" + std::to_string(secondary_.layer_size) + "^2";
    }

    void take_screenshots(int window_width, int window_height) {
        const gl::Functions& gl = window_context_.gl();
        if (input_.screenshot && !shown_.pixels.empty()) {
            // The back buffer is undefined after a swap: draw the last frame again.
            presenter_.show(shown_, window_width, window_height);
            const std::string path = command_.screenshot.empty()
                                         ? "view-" + std::to_string(++screenshot_count_) + ".png"
                                         : command_.screenshot;
            write_window_png(gl, window_width, window_height, path);
            if (!command_.quiet) std::fprintf(stderr, "wrote %s\n", path.c_str());
        }
        input_.screenshot = false;
        if (command_.frames > 0 && rendered_ == command_.frames && !command_.screenshot.empty()) {
            // The back buffer still holds the last frame (no swap yet).
            write_window_png(gl, window_width, window_height, command_.screenshot);
        }
    }

    const ViewCommand& command_;
    SecondaryOptions secondary_;  // the --secondary-* flags
    int width_, height_;
    SceneRequest request_;
    Scene base_;
    ViewState view_;
    const ViewState initial_;
    GlfwSession glfw_;  // before the window and everything on its context, released after them
    GLFWwindow* window_;
    std::optional<GlRenderer> renderer_;  // --backend gl (or auto on a GPU)
    gl::HeadlessContext window_context_;
    std::string timing_label_;
    Presenter presenter_;
    std::optional<GlDofSecondary> dof_secondary_;  // made on the first dof-secondary frame
    std::string scene_name_;
    glm::vec3 centre_;
    Input input_;
    Image shown_;  // the last frame with its overlay
    int rendered_ = 0;
    int screenshot_count_ = 0;
    bool needs_render_ = true;
    std::set<std::string> warned_;  // the worker's warnings, printed once each
    bool cpu_ = false;  // drawn with the cpu backend, progressively (view_progressive.hpp)
    std::unique_ptr<ProgressiveView> progressive_;  // its worker; before the window is gone
};

// The names --method takes in the view: its two methods and their aliases.
std::vector<std::string> view_method_names() {
    std::vector<std::string> names;
    for (const RenderMethod method : {RenderMethod::stochastic, RenderMethod::dof_secondary}) {
        const RenderMethodInfo& info = render_method_info(method);
        names.push_back(info.name);
        names.insert(names.end(), info.aliases.begin(), info.aliases.end());
    }
    return names;
}

}  // namespace

void ViewCommand::add_options(CLI::App& app) {
    SceneFlags::add_options(app, true);
    scene_option = app.get_option("--scene");
    size_option = app.get_option("--size");
    app.add_option("--method", method,
                   "initial method: stochastic (the GL rasterizer) or dof-secondary (one bounce on mirrors and glass; "
                   "without --scene and --size: mirror-sphere at " + std::string(view_dof_secondary_size) + ")")
        ->check(CLI::IsMember(view_method_names()))
        ->capture_default_str();
    SecondaryFlags::add_options(app);
    app.add_option("--frames", frames,
                   "render this many frames, turning the orbit and cycling the cull method between them, then exit "
                   "(0: interactive)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    app.add_option("--backend", backend,
                   "auto, gl or cpu: what draws the frames (auto: cpu when the window's OpenGL is software, "
                   "e.g. llvmpipe, and the method stochastic; cpu refines progressively to --spp)")
        ->check(CLI::IsMember({"auto", "gl", "cpu"}))
        ->capture_default_str();
    app.add_option("--screenshot", screenshot, "PNG of the window (render and overlay) after the last frame");
    app.add_flag("-q,--quiet", quiet, "no controls or per-frame lines");
    app.footer(view_controls_help);
}

int ViewCommand::run() const {
    ViewCommand command = *this;
    const RenderMethod initial_method = parse_render_method(method);
    refuse_secondary_flags(initial_method);
    if (backend == "cpu" && initial_method != RenderMethod::stochastic) {
        throw std::invalid_argument("--backend cpu: the view draws --method stochastic only on the cpu backend; "
                                    "use --backend gl");
    }
    if (initial_method == RenderMethod::dof_secondary) {
        // A frame of the bounce takes seconds on llvmpipe: a smaller window,
        // and a scene with a mirror, unless the user named them.
        if (scene_option == nullptr || scene_option->count() == 0) command.scene = "mirror-sphere";
        if (size_option == nullptr || size_option->count() == 0) command.size = view_dof_secondary_size;
    }
    validate_secondary_options(command.secondary_options());
    int width = 0, height = 0;
    parse_size(command.size, width, height);
    if (!screenshot.empty()) require_writable_folder(screenshot, "--screenshot");
    ViewSession session(command, width, height);
    session.run();
    return 0;
}

}  // namespace blurcull::frontend
