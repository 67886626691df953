#include "app/render_command.hpp"

#include "app/scene_setup.hpp"

#include "render/cpu_backend.hpp"
#include "render/embree_backend.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/image.hpp"
#include "render/interleaved_backend.hpp"
#include "render/render_types.hpp"
#include "scene/builtin_scenes.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {
namespace {

// Memory budget: refuse a render whose buffers cannot fit before allocating
// any. Per pixel: the float RGB image and the 8-bit PNG rows (15 bytes); per
// sample, for the methods that keep every sample (interleave, interval: a
// double depth and a uint32 hit) 12 bytes, for accum 4. The limit is
// MemAvailable from /proc/meminfo (sysconf's available pages without it).
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

void check_memory_budget(const std::string& size_text, int spp, const std::string& method, int width,
                         int height) {
    const double pixels = double(width) * double(height);
    const double per_sample = method == "interleave" || method == "interval" ? 12.0 : (method == "accum" ? 4.0 : 0.0);
    const double needed = pixels * (15.0 + per_sample * spp);
    const double available = available_memory_bytes();
    if (needed > available) {
        char message[256];
        std::snprintf(message, sizeof message,
                      "--size %s --spp %d: the render needs about %.1f GiB of memory but only %.1f GiB is available "
                      "(MemAvailable)",
                      size_text.c_str(), spp, needed / 1073741824.0, available / 1073741824.0);
        throw std::runtime_error(message);
    }
}

}  // namespace

void RenderCommand::add_options(CLI::App& app) {
    SceneFlags::add_options(app, false);
    app.add_option("--backend", backend, "cpu, embree, gl or auto (auto: the best available)")
        ->check(CLI::IsMember({"auto", "cpu", "embree", "gl"}))
        ->capture_default_str();
    app.add_option("--method", method,
                   "stochastic (culled stochastic rasterization), interleave, interval or accum (cpu and gl backends)")
        ->check(CLI::IsMember({"stochastic", "interleave", "interval", "accum"}))
        ->capture_default_str();
    app.add_option("-o,--output", output, "PNG to write (default: <scene>.png in the current folder)");
    app.add_flag("--json", json, "print one JSON object with the render's statistics on stdout");
    app.add_option("--threads", threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
    app.add_option("--footprint", footprint, "cpu: pixels per side of a culling footprint")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    app.add_option("--precision", precision,
                   "cpu: the kernel's arithmetic, double (reference) or float (the gl backend's)")
        ->check(CLI::IsMember({"double", "float"}))
        ->capture_default_str();
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
}

int RenderCommand::run() const {
    RenderSettings settings;
    parse_size(size, settings.width, settings.height);
    check_memory_budget(size, spp, method, settings.width, settings.height);
    settings.spp = spp;
    settings.seed = seed;
    settings.cull = parse_cull_method(cull);
    settings.method = method;
    settings.threads = threads;
    settings.progress = !quiet;
    const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);

    float shutter_open = 0.0f, shutter_close = 1.0f;
    if (!shutter.empty()) parse_shutter(shutter, shutter_open, shutter_close);

    // Refuse before rendering when the output cannot be written.
    const std::string out_path = output.empty() ? stem(scene) + ".png" : output;
    {
        std::size_t slash = out_path.find_last_of('/');
        std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : out_path.substr(0, slash));
        if (access(folder.c_str(), W_OK) != 0) {
            throw std::runtime_error("-o: cannot write '" + out_path + "': folder '" + folder + "' is not writable");
        }
    }

    SceneRequest request;
    request.scene = scene;
    request.aspect = aspect;
    request.blur_scale = blur_scale;
    request.has_shutter = !shutter.empty();
    request.shutter_open = shutter_open;
    request.shutter_close = shutter_close;
    request.lens_radius = lens_radius;
    request.fstop = fstop;
    request.focus = focus;
    const Scene loaded = load_scene(request);

    std::string used_backend = backend;
    if (backend == "auto") {
        // gl on a hardware OpenGL 4.5 context; cpu otherwise (software GL,
        // llvmpipe, is far slower than the cpu backend). One line says which.
        std::string why;
        if (gl_hardware_available(&why)) used_backend = "gl";
        if (used_backend != "gl") used_backend = "cpu";
        if (!quiet) {
            std::fprintf(stderr, "note: --backend auto: using %s (%s)\n", used_backend.c_str(),
                         used_backend == "gl" ? "hardware OpenGL 4.5 context" : ("gl: " + why).c_str());
        }
    }

    if (used_backend == "embree" && method != "stochastic") {
        throw std::runtime_error("--method " + method + ": the embree backend has only stochastic; use --backend cpu or gl");
    }
    if (backend == "gl") {
        std::string why;
        if (!gl_available(&why)) {
            throw std::runtime_error("--backend gl: no OpenGL 4.5 context could be made (" + why +
                                     "); use --backend cpu");
        }
    }
    RenderResult result;
    if (used_backend == "embree") {
        result = render_embree(loaded, settings);
    } else if (used_backend == "gl") {
        result = render_gl(loaded, settings);
    } else if (method != "stochastic") {
        result = render_with_method(loaded, settings);
    } else {
        CpuOptions options;
        options.footprint = footprint;
        options.precision = parse_kernel_precision(precision);
        result = render_cpu(loaded, settings, options);
    }
    write_png(out_path, result.image);

    const RenderStats& stats = result.stats;
    if (json) {
        nlohmann::ordered_json summary;
        summary["scene"] = loaded.name.empty() ? stem(scene) : loaded.name;
        summary["backend"] = used_backend;
        summary["method"] = method;
        summary["cull"] = used_backend == "embree" || method != "stochastic" ? "none" : cull;
        if (used_backend == "cpu" && method == "stochastic") summary["precision"] = precision;
        summary["spp"] = settings.spp;
        summary["width"] = settings.width;
        summary["height"] = settings.height;
        summary["seed"] = settings.seed;
        summary["blur_scale"] = blur_scale;
        summary["lens_radius"] = loaded.camera.lens_radius;
        summary["focus_distance"] = loaded.camera.focus_distance;
        summary["triangles"] = stats.triangles;
        summary["samples_tested"] = stats.samples_tested;
        summary["samples_hit"] = stats.samples_hit;
        summary["ste"] = stats.ste();
        summary["bounds_computed"] = stats.bounds_computed;
        summary["bounds_empty"] = stats.bounds_empty;
        summary["ms_total"] = stats.ms_total;
        nlohmann::ordered_json phases = nlohmann::ordered_json::object();
        for (const auto& [name, ms] : stats.ms_per_phase) phases[name] = ms;
        summary["ms_per_phase"] = phases;
        summary["output"] = out_path;
        std::printf("%s\n", summary.dump().c_str());
    } else {
        // Only the stochastic method culls; the others bound each pass by a box.
        const std::string sampling = settings.method != "stochastic" ? "method " + settings.method
                                     : used_backend == "embree"      ? std::string("cull none")
                                                                     : "cull " + cull;
        std::printf("%s: %zu triangles, %dx%d, %d spp, backend %s, %s\n", scene.c_str(), stats.triangles,
                    settings.width, settings.height, settings.spp, used_backend.c_str(), sampling.c_str());
        std::printf("  %llu samples tested, %llu hit, STE %.1f%%, %.0f ms\n",
                    static_cast<unsigned long long>(stats.samples_tested),
                    static_cast<unsigned long long>(stats.samples_hit), 100.0 * stats.ste(), stats.ms_total);
        std::printf("  wrote %s\n", out_path.c_str());
    }
    return 0;
}

int list_scenes() {
    for (const std::string& name : builtin_scene_names()) std::printf("%s\n", name.c_str());
    return 0;
}

}  // namespace blurcull::frontend
