#include "app/render_command.hpp"

#include "app/frame_sequence.hpp"
#include "app/scene_setup.hpp"

#include "render/common/backend.hpp"
#include "render/common/image.hpp"
#include "render/common/motion_segments.hpp"
#include "render/common/progress.hpp"
#include "render/common/render_types.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/methods.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/gl/gl_backend.hpp"
#if BLURCULL_HAVE_GL
#include "app/gl_dof_secondary.hpp"
#include "render/gl/gl_context.hpp"
#endif
#include "render/secondary/dof_secondary.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/motion_segments.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {
namespace {

// Memory budget: refuse a render whose buffers cannot fit before allocating
// any. Per pixel: the float RGB image, its coverage, and the file's rows
// (8-bit RGB for a PNG, four floats for an EXR: 32 bytes at most); per
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
    const double needed = pixels * (32.0 + per_sample * settings.spp);
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
// backend chosen and its options, where the images go and in which format,
// the frames (none: one render of the scene's own or --shutter's shutter),
// and the scene of the frame being rendered.
struct RenderJob {
    RenderSettings settings;
    Backend backend = Backend::cpu;
    CpuOptions cpu;
    GlOptions gl;
    EmbreeOptions embree;
    SecondaryOptions secondary;
    LayerImagesOn layer_images = LayerImagesOn::gl;  // dof-secondary on gl: where the layers are built
    OutputPattern output;
    ImageFormat format = ImageFormat::png;
    ExrPixelType exr_type = ExrPixelType::half;
    std::vector<long> frames;
    std::optional<long> frame;  // the frame being rendered, in a sequence
    std::string out_path;       // its file
    Scene scene;
#if BLURCULL_HAVE_GL
    // The gl backend's one context for the whole command: the one --backend's
    // probe made (choose_backend, require_gl_context), then the renderer made
    // on it at the first frame and kept for every frame (job_gl_renderer).
    std::unique_ptr<gl::HeadlessContext> gl_context;
    std::optional<GlRenderer> gl_renderer;
#endif
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
    {"secondary layers", "--secondary-layers"}, {"clusters per facet", "--clusters-per-facet"},
    {"secondary field of view", "--secondary-fov"}, {"layer size", "--layer-size"}, {"lens parts", "--lens-parts"},
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
    settings.sampler = parse_sample_pattern(command.sampler);
    settings.threads = command.threads;
    settings.progress = !command.quiet;
    return settings;
}

// The output name (a pattern with a frame field for a sequence) and its
// format; refused before rendering when the type is unknown, the frame
// field is missing or misplaced, or the folder is not writable.
OutputPattern writable_output(const RenderCommand& command, bool sequence, ImageFormat& format) {
    const std::string name = !command.output.empty() ? command.output
                             : sequence              ? stem(command.scene) + "_%04d.png"
                                                     : stem(command.scene) + ".png";
    OutputPattern pattern = parse_output_pattern(name, sequence);
    const std::string first = pattern.path_for(0);
    try {
        format = image_format_for_path(first);
    } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(std::string("-o: ") + error.what());
    }
    const std::size_t slash = first.find_last_of('/');
    if (pattern.has_field && slash != std::string::npos && slash >= pattern.before.size()) {
        throw std::invalid_argument("-o " + name + ": the frame field must be in the file's name, not its folder");
    }
    const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : first.substr(0, slash));
    if (access(folder.c_str(), W_OK) != 0) {
        throw std::runtime_error("-o: cannot write '" + name + "': folder '" + folder + "' is not writable");
    }
    return pattern;
}

// --frames and the options that go with it: the frame numbers (empty
// without --frames); throws naming the flag for a bad range, an angle
// outside (0, 360], an fps that is not positive, or --fps, --shutter-angle
// without --frames and --shutter with it.
std::vector<long> sequence_frames(const RenderCommand& command) {
    const bool fps_given = command.fps_option != nullptr && command.fps_option->count() > 0;
    const bool angle_given = command.shutter_angle_option != nullptr && command.shutter_angle_option->count() > 0;
    if (command.frames_option == nullptr || command.frames_option->count() == 0) {
        if (fps_given) throw std::invalid_argument("--fps: only a sequence takes it (give --frames A:B)");
        if (angle_given) {
            throw std::invalid_argument("--shutter-angle: only a sequence takes it (give --frames A:B, or --shutter "
                                        "OPEN,CLOSE for one frame)");
        }
        return {};
    }
    if (!command.shutter.empty()) {
        throw std::invalid_argument("--shutter: a sequence's shutter comes from --fps and --shutter-angle, not "
                                    "--shutter");
    }
    if (!(command.shutter_angle > 0.0 && command.shutter_angle <= 360.0)) {
        char message[160];
        std::snprintf(message, sizeof message, "--shutter-angle %g: expected degrees in (0, 360]",
                      command.shutter_angle);
        throw std::invalid_argument(message);
    }
    if (!(command.fps > 0.0) || !std::isfinite(command.fps)) {
        char message[160];
        std::snprintf(message, sizeof message, "--fps %g: expected a positive number of frames per second",
                      command.fps);
        throw std::invalid_argument(message);
    }
    return parse_frame_range(command.frames).frames();
}

// --exr-type: the EXR's channel type; refused for a PNG.
ExrPixelType exr_pixel_type(const RenderCommand& command, ImageFormat format) {
    if (format != ImageFormat::exr && command.exr_type_option != nullptr && command.exr_type_option->count() > 0) {
        throw std::invalid_argument("--exr-type: only an .exr output takes it");
    }
    return command.exr_type == "float" ? ExrPixelType::full_float : ExrPixelType::half;
}

// --backend: the one named, or for auto gl on a hardware OpenGL 4.5 context
// (kept in the job: the render's one context) and cpu otherwise (software
// GL, llvmpipe, is far slower than the cpu backend); one line says which.
Backend choose_backend(const RenderCommand& command, [[maybe_unused]] RenderJob& job) {
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
    job.gl_context = hardware_gl_context(&why);
    const Backend chosen = job.gl_context ? Backend::gl : Backend::cpu;
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
        {"--time-strata", command.time_strata_option, backend_bit(Backend::cpu)},
        {"--lens-strata", command.lens_strata_option, backend_bit(Backend::cpu)},
        {"--occlusion", command.occlusion_option, backend_bit(Backend::cpu) | backend_bit(Backend::gl)},
        {"--precision", command.precision_option, backend_bit(Backend::cpu)},
        {"--gl-cell", command.gl_cell_option, backend_bit(Backend::gl)},
        {"--gl-pipeline", command.gl_pipeline_option, backend_bit(Backend::gl)},
        {"--secondary", command.secondary_option, backend_bit(Backend::embree)},
        {"--layer-images", command.layer_images_option, backend_bit(Backend::gl)},
    };
    command.refuse_secondary_flags(method.method);
    const bool own_samples = method.method == RenderMethod::interleave || method.method == RenderMethod::interval ||
                             method.method == RenderMethod::accum;
    if (own_samples && command.sampler_option != nullptr && command.sampler_option->count() > 0) {
        throw std::invalid_argument(std::string("--sampler: method ") + method.name +
                                    " draws its own samples (only stochastic and dof-secondary take it)");
    }
    // The compute pipeline: the stochastic method, and dof-secondary's
    // primary pass, which is that method; no cells (docs/gl-backend.md, "The
    // compute pipeline").
    const bool stochastic_samples =
        method.method == RenderMethod::stochastic || method.method == RenderMethod::dof_secondary;
    if (command.gl_pipeline == "compute" && backend == Backend::gl) {
        if (!stochastic_samples) {
            throw std::invalid_argument(std::string("--gl-pipeline compute: only the stochastic and dof-secondary "
                                                    "methods take it (method ") +
                                        method.name + ")");
        }
        if (command.gl_cell_option != nullptr && command.gl_cell_option->count() > 0) {
            throw std::invalid_argument("--gl-cell: only --gl-pipeline fragment takes it (the compute pipeline bounds "
                                        "samples per 8x8-pixel tile)");
        }
    }
    // On gl, --occlusion is the compute pipeline's (given or chosen by auto below).
    const auto given = [](const CLI::Option* option) { return option != nullptr && option->count() > 0; };
    const bool compute_pipeline =
        stochastic_samples &&
        (command.gl_pipeline == "compute" ||
         (command.backend == "auto" && !given(command.gl_pipeline_option) && !given(command.gl_cell_option)));
    if (backend == Backend::gl && !compute_pipeline && command.occlusion_option != nullptr &&
        command.occlusion_option->count() > 0) {
        throw std::invalid_argument("--occlusion: on gl only --gl-pipeline compute takes it");
    }
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

// --backend gl asked for explicitly: its context made now, kept in the job
// (the render's one context), or refused, with the reason, when none can be.
void require_gl_context([[maybe_unused]] const RenderCommand& command, [[maybe_unused]] RenderJob& job) {
#if BLURCULL_HAVE_GL
    if (command.backend != "gl") return;
    try {
        job.gl_context = std::make_unique<gl::HeadlessContext>(gl::HeadlessContext::create());
    } catch (const gl::GlError& error) {
        throw std::runtime_error(std::string("--backend gl: no OpenGL 4.5 context could be made (") + error.what() +
                                 "); use --backend cpu");
    }
#endif
}

// The frame's shutter on the scene's animation clock (scene/load_scene.hpp).
FrameShutter frame_shutter(const RenderCommand& command, long frame) {
    FrameShutter shutter;
    shutter.frame = frame;
    shutter.fps = command.fps;
    shutter.shutter_angle_degrees = command.shutter_angle;
    return shutter;
}

// The scene, its lens, focus, shutter (or the frame's) and blur-scale
// overrides; throws naming --shutter when it is malformed.
SceneRequest scene_request(const RenderCommand& command, const RenderSettings& settings, std::optional<long> frame) {
    SceneRequest request;
    request.scene = command.scene;
    request.aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    request.blur_scale = command.blur_scale;
    request.has_shutter = !command.shutter.empty();
    if (request.has_shutter) parse_shutter(command.shutter, request.shutter_open, request.shutter_close);
    request.has_frame = frame.has_value();
    if (frame) request.frame = frame_shutter(command, *frame);
    request.lens_radius = command.lens_radius;
    request.fstop = command.fstop;
    request.focus = command.focus;
    request.motion_segments = parse_motion_segments(command.motion_segments);
    request.blend_opaque = command.alpha_blend == "opaque";
    request.image_height = settings.height;
    return request;
}

// Checks the options (all of them, before any frame is rendered); throws
// with a one-line message naming the flag.
RenderJob set_up(const RenderCommand& command) {
    RenderJob job;
    job.settings = make_settings(command);
    check_memory_budget(command.size, job.settings);
    job.frames = sequence_frames(command);
    scene_request(command, job.settings, std::nullopt);  // checks --shutter
    job.output = writable_output(command, !job.frames.empty(), job.format);
    job.exr_type = exr_pixel_type(command, job.format);
    job.backend = choose_backend(command, job);
    refuse_unhonoured_options(command, job.backend);
    require_gl_context(command, job);
    job.cpu.footprint = command.footprint;
    job.cpu.time_strata = command.time_strata;
    job.cpu.lens_strata = command.lens_strata;
    job.cpu.occlusion = command.occlusion == "on";
    job.cpu.precision = parse_kernel_precision(command.precision);
    job.gl.cell_pixels = command.gl_cell;
    job.gl.pipeline = parse_gl_pipeline(command.gl_pipeline);
    job.gl.occlusion = command.occlusion == "on";
    // --backend auto chose gl, so a hardware GPU: the stochastic method (and
    // dof-secondary's primary pass) on the compute pipeline, which uses all
    // of a compute GPU's multiprocessors (docs/gl-backend.md), unless
    // --gl-pipeline or --gl-cell (the fragment pipeline's) says otherwise.
    const auto given = [](const CLI::Option* option) { return option != nullptr && option->count() > 0; };
    const bool stochastic_samples =
        job.settings.method == RenderMethod::stochastic || job.settings.method == RenderMethod::dof_secondary;
    if (command.backend == "auto" && job.backend == Backend::gl && stochastic_samples &&
        !given(command.gl_pipeline_option) && !given(command.gl_cell_option)) {
        job.gl.pipeline = GlPipeline::compute;
    }
#if BLURCULL_HAVE_EMBREE
    job.embree.secondary = parse_embree_secondary(command.secondary);
#endif
    job.secondary = command.secondary_options();
    job.layer_images = command.layer_images == "host"          ? LayerImagesOn::host
                       : command.layer_images == "gl-readback" ? LayerImagesOn::gl_readback
                                                               : LayerImagesOn::gl;
    try {
        validate_secondary_options(job.secondary);
    } catch (const std::invalid_argument& error) {
        throw naming_the_flag(error);
    }
    return job;
}

#if BLURCULL_HAVE_GL
// The job's GL renderer: made at the first frame on the context --backend's
// probe made, and kept for the others. `made_ms`: what making it took (0
// when it was kept).
GlRenderer& job_gl_renderer(RenderJob& job, double& made_ms) {
    made_ms = 0.0;
    if (!job.gl_renderer) {
        const RenderClock::time_point start = RenderClock::now();
        // set_up made the context for gl; a fresh one only if it did not.
        job.gl_renderer.emplace(job.gl_context ? std::move(*job.gl_context) : gl::HeadlessContext::create());
        job.gl_context.reset();
        made_ms = ms_since(start);
    }
    return *job.gl_renderer;
}
#endif

// dof-secondary: on gl the primary samples, the layers (unless --layer-images
// host) and the image-space traces run on GL (app/gl_dof_secondary.hpp).
RenderResult render_secondary(RenderJob& job) {
#if BLURCULL_HAVE_GL
    if (job.backend == Backend::gl) {
        // The rasterizer, the layer and the trace passes on the one context
        // (as blurcull view runs them on its window's).
        double made_ms = 0.0;
        GlRenderer& rasterizer = job_gl_renderer(job, made_ms);
        return GlDofSecondary(rasterizer, rasterizer.context())
            .render(job.scene, job.settings, job.gl, job.secondary, nullptr, job.layer_images);
    }
#endif
    return render_dof_secondary(job.scene, job.settings, job.secondary);
}

// Loads the scene of `frame` (none: the single render's) into the job.
// The scene's warnings are printed for the first load only: every frame
// of a file would repeat them.
void load_frame(const RenderCommand& command, RenderJob& job, std::optional<long> frame, bool print_warnings) {
    job.frame = frame;
    job.out_path = job.output.path_for(frame.value_or(0));
    const SceneRequest request = scene_request(command, job.settings, frame);
    job.scene = print_warnings ? load_scene(request) : load_scene(request.scene, request, WarningSink{});
    // Motion segments chosen by auto (the default) where the backend or
    // method carries one linear motion per triangle: the chords, warned.
    const bool follows_segments = job.settings.method == RenderMethod::stochastic &&
                                  (job.backend == Backend::cpu || job.backend == Backend::embree);
    if (!follows_segments && job.scene.motion_segments_auto && scene_motion_segments(job.scene) > 1) {
        const std::string who = job.backend == Backend::gl ? std::string("gl")
                                                           : std::string("method ") + to_string(job.settings.method);
        const int dropped = drop_motion_segments(job.scene);
        if (print_warnings) std::fprintf(stderr, "warning: %s\n", dropped_motion_segments_warning(who, dropped).c_str());
    }
}

// The frame's shutter open time on the scene's clock.
double frame_open_time(const RenderCommand& command, long frame) {
    return frame_shutter_interval(command.scene, frame_shutter(command, frame)).first;
}

// The sequence's frames whose shutter opens within the animation
// (job.scene, the first frame's, says where it ends): refused when the
// first opens after the end, cut with a warning when later ones do.
void keep_frames_in_animation(const RenderCommand& command, RenderJob& job) {
    const double end = job.scene.animation_end;
    const double slack = 1e-6 * std::max(1.0, std::abs(end));  // the end is a float keyframe time
    const auto past_end = [&](long frame) { return frame_open_time(command, frame) > end + slack; };
    if (past_end(job.frames.front())) {
        char message[320];
        std::snprintf(message, sizeof message,
                      "--frames %s: frame %ld opens at %g s, after the animation of '%s' ends (%g s, frame %ld at "
                      "--fps %g)",
                      command.frames.c_str(), job.frames.front(), frame_open_time(command, job.frames.front()),
                      command.scene.c_str(), end, static_cast<long>(std::floor((end + slack) * command.fps)), command.fps);
        throw std::invalid_argument(message);
    }
    if (!past_end(job.frames.back())) return;
    while (past_end(job.frames.back())) job.frames.pop_back();
    if (!command.quiet) {
        std::fprintf(stderr,
                     "warning: --frames %s: the animation of '%s' ends at %g s; rendering frames %ld to %ld (the last "
                     "that open before it)\n",
                     command.frames.c_str(), command.scene.c_str(), end, job.frames.front(), job.frames.back());
    }
}

// Renders on the job's backend with its method. Where the method forks:
// here for cpu (render_with_method or render_cpu); inside the backend for
// embree (render_embree) and gl (GlRenderer::render: render_gl_method or
// the stochastic frame).
RenderResult dispatch(RenderJob& job) {
    try {
        if (job.settings.method == RenderMethod::dof_secondary) return render_secondary(job);
        // choose_backend refused the backends this build does not have.
        switch (job.backend) {
#if BLURCULL_HAVE_EMBREE
            case Backend::embree: return render_embree(job.scene, job.settings, job.embree);
#endif
#if BLURCULL_HAVE_GL
            case Backend::gl: {
                double made_ms = 0.0;
                GlRenderer& renderer = job_gl_renderer(job, made_ms);
                return render_gl_frame(renderer, job.scene, job.settings, job.gl, made_ms);
            }
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
    if (job.frame) {
        const std::pair<double, double> shutter = frame_shutter_interval(command.scene, frame_shutter(command, *job.frame));
        summary["frame"] = *job.frame;
        summary["fps"] = command.fps;
        summary["shutter_angle"] = command.shutter_angle;
        summary["shutter_open"] = shutter.first;
        summary["shutter_close"] = shutter.second;
    }
    summary["backend"] = to_string(job.backend);
    summary["method"] = to_string(job.settings.method);
    summary["cull"] = culled(job) ? to_string(job.settings.cull) : "none";
    if (job.backend == Backend::gl) {
        if (job.settings.method == RenderMethod::stochastic || job.settings.method == RenderMethod::dof_secondary)
            summary["gl_pipeline"] = to_string(job.gl.pipeline);  // dof-secondary: its primary pass's
#if BLURCULL_HAVE_GL
        if (job.gl_renderer) summary["gl_renderer"] = job.gl_renderer->description();
#endif
    }
    if (job.backend == Backend::cpu && job.settings.method == RenderMethod::stochastic) {
        summary["precision"] = to_string(job.cpu.precision);
    }
    summary["spp"] = job.settings.spp;
    summary["width"] = job.settings.width;
    summary["height"] = job.settings.height;
    summary["seed"] = job.settings.seed;
    if (job.settings.method == RenderMethod::stochastic || job.settings.method == RenderMethod::dof_secondary) {
        summary["sampler"] = sample_pattern_name(job.settings.sampler);  // the others draw their own samples
    }
    summary["blur_scale"] = command.blur_scale;
    summary["lens_radius"] = job.scene.camera.lens_radius;
    summary["focus_distance"] = job.scene.camera.focus_distance;
    summary["triangles"] = stats.triangles;
    summary["motion_segments"] = scene_motion_segments(job.scene);
    summary["alpha_blend"] = command.alpha_blend;
    summary["samples_tested"] = stats.samples_tested;
    summary["samples_hit"] = stats.samples_hit;
    if (stats.secondary_rays > 0) summary["secondary_rays"] = stats.secondary_rays;
    if (stats.samples_visited > 0) summary["samples_visited"] = stats.samples_visited;
    summary["ste"] = stats.ste();
    summary["bounds_computed"] = stats.bounds_computed;
    summary["bounds_empty"] = stats.bounds_empty;
    summary["ms_total"] = stats.ms_total;
    nlohmann::ordered_json phases = nlohmann::ordered_json::object();
    for (const auto& [name, ms] : stats.ms_per_phase) phases[name] = ms;
    summary["ms_per_phase"] = phases;
    if (!stats.counters.empty()) {
        nlohmann::ordered_json counters = nlohmann::ordered_json::object();
        for (const auto& [name, value] : stats.counters) counters[name] = value;
        summary["counters"] = counters;
    }
    summary["output"] = job.out_path;
    summary["format"] = job.format == ImageFormat::png ? "png" : "exr";
    summary["encoding"] = image_encoding(job.format, job.exr_type);
    std::printf("%s\n", summary.dump().c_str());
    std::fflush(stdout);  // a sequence's lines as its frames finish
}

void print_text_summary(const RenderCommand& command, const RenderJob& job, const RenderStats& stats) {
    const std::string sampling = job.settings.method != RenderMethod::stochastic
                                     ? std::string("method ") + to_string(job.settings.method)
                                     : std::string("cull ") + (culled(job) ? to_string(job.settings.cull) : "none");
    const std::string frame = job.frame ? " frame " + std::to_string(*job.frame) : std::string();
    std::printf("%s%s: %zu triangles, %dx%d, %d spp, backend %s, %s\n", command.scene.c_str(), frame.c_str(),
                stats.triangles, job.settings.width, job.settings.height, job.settings.spp, to_string(job.backend),
                sampling.c_str());
    std::printf("  %llu samples tested, %llu hit, STE %.1f%%, %.0f ms\n",
                static_cast<unsigned long long>(stats.samples_tested),
                static_cast<unsigned long long>(stats.samples_hit), 100.0 * stats.ste(), stats.ms_total);
    std::printf("  wrote %s (%s)\n", job.out_path.c_str(), image_encoding(job.format, job.exr_type).c_str());
    std::fflush(stdout);
}

// Renders the job's frame, writes its file and prints its summary.
void render_and_write(const RenderCommand& command, RenderJob& job) {
    const RenderResult result = dispatch(job);
    for (const std::string& warning : result.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    if (job.format == ImageFormat::exr && result.image.coverage.empty()) {
        std::fprintf(stderr, "warning: backend %s, method %s did not report coverage: the EXR's alpha is 1\n",
                     to_string(job.backend), to_string(job.settings.method));
    }
    write_image(job.out_path, result.image, job.format, job.exr_type);
    if (command.json) {
        print_json_summary(command, job, result.stats);
    } else {
        print_text_summary(command, job, result.stats);
    }
}

// "frame 12: 3 of 10 (30%), 1.4 s per frame, about 9.8 s left" on stderr.
void report_sequence_progress(const RenderJob& job, std::size_t done, RenderClock::time_point start) {
    const double seconds = ms_since(start) / 1000.0;
    const double per_frame = seconds / static_cast<double>(done);
    std::fprintf(stderr, "frame %ld: %zu of %zu (%d%%), %.2f s per frame, about %.1f s left\n", *job.frame, done,
                 job.frames.size(), static_cast<int>(100 * done / job.frames.size()), per_frame,
                 per_frame * static_cast<double>(job.frames.size() - done));
}

// Every frame of the sequence, each loaded, rendered and written on its own
// (a frame depends on nothing but its number and the options).
void render_sequence(const RenderCommand& command, RenderJob& job) {
    const RenderClock::time_point start = RenderClock::now();
    load_frame(command, job, job.frames.front(), true);
    keep_frames_in_animation(command, job);
    for (std::size_t i = 0; i < job.frames.size(); ++i) {
        if (i > 0) load_frame(command, job, job.frames[i], false);
        render_and_write(command, job);
        if (!command.quiet) report_sequence_progress(job, i + 1, start);
    }
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
    std::vector<std::string> samplers;
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) samplers.emplace_back(sample_pattern_name(pattern));
    sampler_option = app.add_option("--sampler", sampler,
                                    "sample pattern of the stochastic renderers: " + sample_pattern_list() +
                                        " (docs/sampling.md)")
                         ->check(CLI::IsMember(samplers))
                         ->capture_default_str();
    app.add_option("-o,--output", output,
                   "image to write, .png (sRGB 8-bit) or .exr (linear RGBA, alpha = coverage); for --frames a name "
                   "with a frame field such as %04d (default: <scene>.png, <scene>_%04d.png for --frames)");
    exr_type_option = app.add_option("--exr-type", exr_type, "an .exr output's channels: half or float")
                          ->check(CLI::IsMember({"half", "float"}))
                          ->capture_default_str();
    frames_option = app.add_option("--frames", frames,
                   "A:B[:STEP]: render frames A to B (included) of the animation, each to its own file (-o's frame "
                   "field); glTF frame f opens at f / fps seconds, a built-in scene's frame f at f times its nominal "
                   "shutter");
    fps_option = app.add_option("--fps", fps, "frames per second of --frames")->capture_default_str();
    shutter_angle_option =
        app.add_option("--shutter-angle", shutter_angle,
                       "degrees of each frame interval the shutter is open, in (0, 360] (180: half, opening at the "
                       "frame's time)")
            ->capture_default_str();
    app.add_flag("--json", json, "print one JSON object with the render's statistics on stdout");
    app.add_option("--threads", threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
    footprint_option = app.add_option("--footprint", footprint, "cpu: pixels per side of a culling footprint")
                           ->check(CLI::Range(1, 64))
                           ->capture_default_str();
    time_strata_option =
        app.add_option("--time-strata", time_strata,
                       "cpu, bbox and hull: shutter slices a moving triangle's samples are tested in, each in its "
                       "own screen box (1, 2, 4, 8 or 16; 1: off)")
            ->check(CLI::IsMember({1, 2, 4, 8, 16}))
            ->capture_default_str();
    lens_strata_option =
        app.add_option("--lens-strata", lens_strata,
                       "cpu, bbox and hull: parts of the lens along u and along v a defocused triangle's samples are "
                       "tested in, each in its own screen box (1, 2 or 4; 1: off)")
            ->check(CLI::IsMember({1, 2, 4}))
            ->capture_default_str();
    occlusion_option =
        app.add_option("--occlusion", occlusion,
                       "cpu, bbox and hull: skip a moving triangle's samples that nearer triangles already hold; "
                       "gl --gl-pipeline compute, every cull: skip a tile's triangles behind all it holds (on or "
                       "off; the same image, fewer samples tested and counted in samples_hit)")
            ->check(CLI::IsMember({"on", "off"}))
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
    gl_pipeline_option = app.add_option("--gl-pipeline", gl_pipeline,
                                        "gl, stochastic method: fragment (MSAA passes of four samples) or compute "
                                        "(binned to screen tiles, a work group per tile); the same image")
                             ->check(CLI::IsMember({"fragment", "compute"}))
                             ->capture_default_str();
    secondary_option = app.add_option("--secondary", secondary,
                                      "embree: what a ray that hits a mirror or glass sees; bounce: one exact bounce "
                                      "of reflection and refraction; none: the primary-only image (the environment "
                                      "along the bounced pinhole ray, as the cpu and gl backends)")
                           ->check(CLI::IsMember({"bounce", "none"}))
                           ->capture_default_str();
    SecondaryFlags::add_options(app);
    layer_images_option = app.add_option("--layer-images", layer_images,
                                         "dof-secondary on gl: build the clusters' layered images and depth "
                                         "pyramids with the GL rasterizer and compute passes and bounce the rays "
                                         "there (gl); the same layers read back for the host's clipping (gl-readback); "
                                         "or build them on the host with the cpu backend's code (host)")
                              ->check(CLI::IsMember({"gl", "gl-readback", "host"}))
                              ->capture_default_str();
    dof_secondary_options.push_back(layer_images_option);  // refused with the other methods
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
}

int RenderCommand::run() const {
    RenderJob job = set_up(*this);
    if (!job.frames.empty()) {
        render_sequence(*this, job);
        return 0;
    }
    load_frame(*this, job, std::nullopt, true);
    render_and_write(*this, job);
    return 0;
}

int list_scenes() {
    // One scene a line: the name, spaces to a common column, the description
    // (`blurcull scenes | cut -d' ' -f1` gives the names).
    const std::vector<BuiltinSceneInfo> scenes = builtin_scene_catalogue();
    std::size_t width = 0;
    for (const BuiltinSceneInfo& scene : scenes) width = std::max(width, scene.name.size());
    for (const BuiltinSceneInfo& scene : scenes)
        std::printf("%-*s  %s\n", static_cast<int>(width), scene.name.c_str(), scene.description.c_str());
    return 0;
}

}  // namespace blurcull::frontend
