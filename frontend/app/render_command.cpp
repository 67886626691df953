#include "app/render_command.hpp"

#include "app/scene_setup.hpp"

#include "render/common/backend.hpp"
#include "render/common/image.hpp"
#include "render/common/render_types.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/methods.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/gl/gl_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::frontend {
namespace {

// Memory budget: refuse a render whose buffers cannot fit before allocating
// any. Per pixel: the float RGB image and the 8-bit PNG rows (15 bytes); per
// sample what the method's registry entry says its CPU renderer keeps. The
// limit is MemAvailable from /proc/meminfo (sysconf's available pages without it).
double available_memory_bytes() {
    if (FILE* meminfo = std::fopen("/proc/meminfo", "r")) {
        char line[256];
        double kib = -1.0;
        while (std::fgets(line, sizeof line, meminfo)) {
            if (std::sscanf(line, "MemAvailable: %lf kB", &kib) == 1) break;
        }
        std::fclose(meminfo);
        if (kib >= 0.0) return kib * 1024.0;
    }
    return double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
}

void check_memory_budget(const std::string& size_text, const RenderSettings& settings) {
    const double pixels = double(settings.width) * double(settings.height);
    const double per_sample = render_method_info(settings.method).bytes_per_sample;
    const double needed = pixels * (15.0 + per_sample * settings.spp);
    const double available = available_memory_bytes();
    if (needed > available) {
        char message[256];
        std::snprintf(message, sizeof message,
                      "--size %s --spp %d: the render needs about %.1f GiB of memory but only %.1f GiB is available "
                      "(MemAvailable)",
                      size_text.c_str(), settings.spp, needed / 1073741824.0, available / 1073741824.0);
        throw std::runtime_error(message);
    }
}

// Everything a render needs once the options are checked: the settings, the
// backend chosen and its options, where the PNG goes, and the scene.
struct RenderJob {
    RenderSettings settings;
    Backend backend = Backend::cpu;
    CpuOptions cpu;
    GlOptions gl;
    std::string out_path;
    Scene scene;
};

// The flag of each setting the render layer's errors name, for the command
// to add when it reports them.
struct SettingFlag {
    const char* setting;
    const char* flag;
};
constexpr SettingFlag setting_flags[] = {
    {"image size", "--size"},           {"samples per pixel", "--spp"},    {"thread count", "--threads"},
    {"footprint", "--footprint"},       {"kernel precision", "--precision"}, {"cell_pixels", "--gl-cell"},
};

// `error` with the flag of the setting it names in front ("--spp: interleave:
// samples per pixel must be a square ..."); unchanged when it names none.
std::invalid_argument naming_the_flag(const std::invalid_argument& error) {
    const std::string message = error.what();
    for (const SettingFlag& entry : setting_flags) {
        if (message.find(entry.setting) != std::string::npos) {
            return std::invalid_argument(std::string(entry.flag) + ": " + message);
        }
    }
    return error;
}

RenderSettings make_settings(const RenderCommand& command) {
    RenderSettings settings;
    parse_size(command.size, settings.width, settings.height);
    settings.spp = command.spp;
    settings.seed = command.seed;
    settings.cull = parse_cull_method(command.cull);
    settings.method = parse_render_method(command.method);
    settings.threads = command.threads;
    settings.progress = !command.quiet;
    return settings;
}

// The PNG's path; refused before rendering when its folder is not writable.
std::string writable_output_path(const RenderCommand& command) {
    const std::string out_path = command.output.empty() ? stem(command.scene) + ".png" : command.output;
    const std::size_t slash = out_path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : out_path.substr(0, slash));
    if (access(folder.c_str(), W_OK) != 0) {
        throw std::runtime_error("-o: cannot write '" + out_path + "': folder '" + folder + "' is not writable");
    }
    return out_path;
}

// --backend: the one named, or for auto gl on a hardware OpenGL 4.5 context
// and cpu otherwise (software GL, llvmpipe, is far slower than the cpu
// backend); one line says which.
Backend choose_backend(const RenderCommand& command) {
    if (command.backend != "auto") {
        const Backend named = parse_backend(command.backend);
        if (!backend_built(named)) {
            throw std::runtime_error("--backend " + command.backend + ": " + backend_missing_reason(named) +
                                     "; use --backend cpu");
        }
        return named;
    }
    std::string why = backend_missing_reason(Backend::gl);
#if BLURCULL_HAVE_GL
    const Backend chosen = gl_hardware_available(&why) ? Backend::gl : Backend::cpu;
#else
    const Backend chosen = Backend::cpu;
#endif
    if (!command.quiet) {
        std::fprintf(stderr, "note: --backend auto: using %s (%s)\n", to_string(chosen),
                     chosen == Backend::gl ? "hardware OpenGL 4.5 context" : ("gl: " + why).c_str());
    }
    return chosen;
}

// Refuses, with one line naming the option and the backends that take it,
// every option given that `backend` cannot honour.
void refuse_unhonoured_options(const RenderCommand& command, Backend backend) {
    const std::string used = std::string("backend ") + to_string(backend) +
                             (command.backend == "auto" ? ", chosen by --backend auto" : "");
    const RenderMethodInfo& method = render_method_info(parse_render_method(command.method));
    if (!takes(method.backends, backend)) {
        throw std::invalid_argument("--method " + command.method + ": " + only_backends_take_it(method.backends) +
                                    " (" + used + ")");
    }
    struct BackendOption {
        const char* flag;
        const CLI::Option* option;
        BackendSet backends;
    };
    const BackendOption options[] = {
        {"--footprint", command.footprint_option, backend_bit(Backend::cpu)},
        {"--precision", command.precision_option, backend_bit(Backend::cpu)},
        {"--gl-cell", command.gl_cell_option, backend_bit(Backend::gl)},
    };
    for (const BackendOption& option : options) {
        if (option.option == nullptr || option.option->count() == 0) continue;
        if (!takes(option.backends, backend)) {
            throw std::invalid_argument(std::string(option.flag) + ": " + only_backends_take_it(option.backends) +
                                        " (" + used + ")");
        }
        // The cpu backend's options are those of its stochastic rasterizer.
        if (backend == Backend::cpu && method.method != RenderMethod::stochastic) {
            throw std::invalid_argument(std::string(option.flag) + ": only the stochastic method takes it (method " +
                                        method.name + ")");
        }
    }
}

// --backend gl asked for explicitly: refused, with the reason, when no
// context can be made.
void require_gl_context([[maybe_unused]] const RenderCommand& command) {
#if BLURCULL_HAVE_GL
    if (command.backend != "gl") return;
    std::string why;
    if (!gl_available(&why)) {
        throw std::runtime_error("--backend gl: no OpenGL 4.5 context could be made (" + why + "); use --backend cpu");
    }
#endif
}

// The scene, its lens, focus, shutter and blur-scale overrides; throws naming
// --shutter when it is malformed.
SceneRequest scene_request(const RenderCommand& command, const RenderSettings& settings) {
    SceneRequest request;
    request.scene = command.scene;
    request.aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    request.blur_scale = command.blur_scale;
    request.has_shutter = !command.shutter.empty();
    if (request.has_shutter) parse_shutter(command.shutter, request.shutter_open, request.shutter_close);
    request.lens_radius = command.lens_radius;
    request.fstop = command.fstop;
    request.focus = command.focus;
    return request;
}

// Checks the options and loads the scene; throws with a one-line message
// naming the flag.
RenderJob set_up(const RenderCommand& command) {
    RenderJob job;
    job.settings = make_settings(command);
    check_memory_budget(command.size, job.settings);
    const SceneRequest request = scene_request(command, job.settings);
    job.out_path = writable_output_path(command);
    job.backend = choose_backend(command);
    refuse_unhonoured_options(command, job.backend);
    require_gl_context(command);
    job.cpu.footprint = command.footprint;
    job.cpu.precision = parse_kernel_precision(command.precision);
    job.gl.cell_pixels = command.gl_cell;
    job.scene = load_scene(request);
    return job;
}

// Renders on the job's backend with its method.
RenderResult dispatch(const RenderJob& job) {
    try {
        // choose_backend refused the backends this build does not have.
        switch (job.backend) {
#if BLURCULL_HAVE_EMBREE
            case Backend::embree: return render_embree(job.scene, job.settings);
#endif
#if BLURCULL_HAVE_GL
            case Backend::gl: return render_gl(job.scene, job.settings, job.gl);
#endif
            default: break;
        }
        if (job.settings.method != RenderMethod::stochastic) return render_with_method(job.scene, job.settings);
        return render_cpu(job.scene, job.settings, job.cpu);
    } catch (const std::invalid_argument& error) {
        throw naming_the_flag(error);
    }
}

// What culled the samples: the cull method when the method culls on this
// backend, else none (the other methods bound each pass by a box).
bool culled(const RenderJob& job) {
    return render_method_info(job.settings.method).culls &&
           takes(cull_method_info(job.settings.cull).backends, job.backend);
}

void print_json_summary(const RenderCommand& command, const RenderJob& job, const RenderStats& stats) {
    nlohmann::ordered_json summary;
    summary["scene"] = job.scene.name.empty() ? stem(command.scene) : job.scene.name;
    summary["backend"] = to_string(job.backend);
    summary["method"] = to_string(job.settings.method);
    summary["cull"] = culled(job) ? to_string(job.settings.cull) : "none";
    if (job.backend == Backend::cpu && job.settings.method == RenderMethod::stochastic) {
        summary["precision"] = to_string(job.cpu.precision);
    }
    summary["spp"] = job.settings.spp;
    summary["width"] = job.settings.width;
    summary["height"] = job.settings.height;
    summary["seed"] = job.settings.seed;
    summary["blur_scale"] = command.blur_scale;
    summary["lens_radius"] = job.scene.camera.lens_radius;
    summary["focus_distance"] = job.scene.camera.focus_distance;
    summary["triangles"] = stats.triangles;
    summary["samples_tested"] = stats.samples_tested;
    summary["samples_hit"] = stats.samples_hit;
    if (stats.samples_visited > 0) summary["samples_visited"] = stats.samples_visited;
    summary["ste"] = stats.ste();
    summary["bounds_computed"] = stats.bounds_computed;
    summary["bounds_empty"] = stats.bounds_empty;
    summary["ms_total"] = stats.ms_total;
    nlohmann::ordered_json phases = nlohmann::ordered_json::object();
    for (const auto& [name, ms] : stats.ms_per_phase) phases[name] = ms;
    summary["ms_per_phase"] = phases;
    summary["output"] = job.out_path;
    std::printf("%s\n", summary.dump().c_str());
}

void print_text_summary(const RenderCommand& command, const RenderJob& job, const RenderStats& stats) {
    const std::string sampling = job.settings.method != RenderMethod::stochastic
                                     ? std::string("method ") + to_string(job.settings.method)
                                     : std::string("cull ") + (culled(job) ? to_string(job.settings.cull) : "none");
    std::printf("%s: %zu triangles, %dx%d, %d spp, backend %s, %s\n", command.scene.c_str(), stats.triangles,
                job.settings.width, job.settings.height, job.settings.spp, to_string(job.backend), sampling.c_str());
    std::printf("  %llu samples tested, %llu hit, STE %.1f%%, %.0f ms\n",
                static_cast<unsigned long long>(stats.samples_tested),
                static_cast<unsigned long long>(stats.samples_hit), 100.0 * stats.ste(), stats.ms_total);
    std::printf("  wrote %s\n", job.out_path.c_str());
}

std::string joined(const std::vector<std::string>& names, const char* separator) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
    return text;
}

}  // namespace

void RenderCommand::add_options(CLI::App& app) {
    SceneFlags::add_options(app, false);
    std::vector<std::string> backends = backend_names();
    backends.insert(backends.begin(), "auto");
    app.add_option("--backend", backend, joined(backends, ", ") + " (auto: the best available)")
        ->check(CLI::IsMember(backends))
        ->capture_default_str();
    method_option = app.add_option("--method", method, render_method_help())
                        ->check(CLI::IsMember(render_method_names_and_aliases()))
                        ->capture_default_str();
    app.add_option("-o,--output", output, "PNG to write (default: <scene>.png in the current folder)");
    app.add_flag("--json", json, "print one JSON object with the render's statistics on stdout");
    app.add_option("--threads", threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
    footprint_option = app.add_option("--footprint", footprint, "cpu: pixels per side of a culling footprint")
                           ->check(CLI::Range(1, 64))
                           ->capture_default_str();
    std::string precision_help = "cpu: the kernel's arithmetic";
    for (const KernelPrecisionInfo& info : kernel_precisions()) {
        precision_help += std::string("; ") + info.name + ": " + info.help;
    }
    precision_option = app.add_option("--precision", precision, precision_help)
                           ->check(CLI::IsMember(kernel_precision_names()))
                           ->capture_default_str();
    gl_cell_option = app.add_option("--gl-cell", gl_cell,
                                    "gl: smallest side, in pixels, of the cells a moving triangle's sample bounds are "
                                    "computed for")
                         ->check(CLI::Range(1, 4096))
                         ->capture_default_str();
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
}

int RenderCommand::run() const {
    const RenderJob job = set_up(*this);
    const RenderResult result = dispatch(job);
    for (const std::string& warning : result.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    write_png(job.out_path, result.image);
    if (json) {
        print_json_summary(*this, job, result.stats);
    } else {
        print_text_summary(*this, job, result.stats);
    }
    return 0;
}

int list_scenes() {
    for (const std::string& name : builtin_scene_names()) std::printf("%s\n", name.c_str());
    return 0;
}

}  // namespace blurcull::frontend
