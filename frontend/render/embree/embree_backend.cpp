#include "render/embree/embree_backend.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/motion_segments.hpp"
#include "render/common/pixel_samples.hpp"
#include "render/common/progress.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "render/embree/primary_rays.hpp"
#include "render/embree/secondary_rays.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace blurcull::frontend {
namespace {

using Clock = std::chrono::steady_clock;

bool has_specular_material(const Scene& scene) {
    for (const Material& material : scene.materials) {
        if (material.kind != MaterialKind::diffuse) return true;
    }
    return false;
}


const char* error_name(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_UNKNOWN: return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error";
}

// Owns an Embree device and remembers the first error it reports. Embree
// calls the error callback from C code, so it records instead of throwing;
// check() turns the record into an exception at a safe point.
class Device {
public:
    explicit Device(unsigned thread_count) {
        std::string config = "threads=" + std::to_string(thread_count);
        handle_ = rtcNewDevice(config.c_str());
        if (handle_ == nullptr) {
            throw std::runtime_error(std::string("embree: cannot create device: ") +
                                     error_name(rtcGetDeviceError(nullptr)));
        }
        rtcSetDeviceErrorFunction(handle_, &Device::on_error, this);
    }
    ~Device() { rtcReleaseDevice(handle_); }
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    RTCDevice get() const { return handle_; }

    void check(const char* step) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!first_error_.empty()) throw std::runtime_error(std::string("embree: ") + step + ": " + first_error_);
    }

private:
    static void on_error(void* user, RTCError code, const char* message) {
        auto* self = static_cast<Device*>(user);
        std::lock_guard<std::mutex> lock(self->mutex_);
        if (!self->first_error_.empty()) return;
        self->first_error_ = error_name(code);
        if (message != nullptr && message[0] != '\0') self->first_error_ += std::string(" (") + message + ")";
    }

    RTCDevice handle_ = nullptr;
    std::mutex mutex_;
    std::string first_error_;
};

class SceneHandle {
public:
    explicit SceneHandle(RTCScene handle) : handle_(handle) {}
    ~SceneHandle() {
        if (handle_ != nullptr) rtcReleaseScene(handle_);
    }
    SceneHandle(const SceneHandle&) = delete;
    SceneHandle& operator=(const SceneHandle&) = delete;
    RTCScene get() const { return handle_; }

private:
    RTCScene handle_;
};

// A sample as the resolve and the alpha test see it (the ray's own inputs).
struct RowSample {
    glm::vec2 ndc, lens;
    float time;
};

// The alpha mask in Embree's nearest-hit search, so a masked-out sample never
// wins: a candidate hit on a MASK triangle is refused unless
// SurfaceShader::sample_kept keeps it (the CPU backend's same call). The
// geometry's user data is the shader; the context's, the traced row's samples
// (ray id = index in the row). A bounced ray (secondary_rays.cpp) carries no
// samples: every hit of it is kept (masks are opaque to secondary rays).
void alpha_mask_filter(const RTCFilterFunctionNArguments* args) {
    const auto* shader = static_cast<const SurfaceShader*>(args->geometryUserPtr);
    const auto* samples = static_cast<const RowSample*>(reinterpret_cast<const TraceContext*>(args->context)->user);
    if (samples == nullptr) return;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
        const RowSample& s = samples[RTCRayN_id(args->ray, args->N, i)];
        if (!shader->sample_kept(triangle, s.ndc, s.lens, s.time)) args->valid[i] = 0;
    }
}

// One triangle mesh with K + 1 time steps (K motion segments, 1 by default)
// holding the VIEW-space vertex positions at the shutter times k / K; Embree
// interpolates linearly between the two steps around ray.time, which is
// exactly the shared motion model (render/common/motion_segments.hpp).
// Masked materials get alpha_mask_filter.
void add_moving_mesh(Device& device, RTCScene rtc_scene, const Scene& scene, const CameraModel& model,
                     const SurfaceShader& shader) {
    if (scene.triangles.empty()) return;
    constexpr std::size_t embree_limit = std::numeric_limits<std::uint32_t>::max();
    if (scene.position_open.size() > embree_limit || scene.triangles.size() > embree_limit) {
        throw std::invalid_argument("scene '" + scene.name + "' has too many vertices or triangles for Embree");
    }
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    device.check("creating the triangle geometry");
    const int segments = scene_motion_segments(scene);
    rtcSetGeometryTimeStepCount(geometry, static_cast<unsigned>(segments + 1));
    const std::size_t vertex_count = scene.position_open.size();
    for (unsigned shutter_end = 0; shutter_end <= static_cast<unsigned>(segments); ++shutter_end) {
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, shutter_end, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertex_count));
        if (vertices == nullptr) {
            rtcReleaseGeometry(geometry);
            device.check("allocating the vertex buffer");
            throw std::runtime_error("embree: cannot allocate the vertex buffer");
        }
        for (std::size_t v = 0; v < vertex_count; ++v) {
            const glm::vec3 view = segments == 1 ? model.view_position(scene, v, static_cast<int>(shutter_end))
                                                 : step_view_position<float>(scene, model, v, static_cast<int>(shutter_end));
            vertices[3 * v + 0] = view.x;
            vertices[3 * v + 1] = view.y;
            vertices[3 * v + 2] = view.z;
        }
    }
    auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), scene.triangles.size()));
    if (indices == nullptr) {
        rtcReleaseGeometry(geometry);
        device.check("allocating the index buffer");
        throw std::runtime_error("embree: cannot allocate the index buffer");
    }
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        indices[3 * t + 0] = scene.triangles[t].x;
        indices[3 * t + 1] = scene.triangles[t].y;
        indices[3 * t + 2] = scene.triangles[t].z;
    }
    if (shader.any_masked()) {
        rtcSetGeometryUserData(geometry, const_cast<SurfaceShader*>(&shader));
        rtcSetGeometryIntersectFilterFunction(geometry, &alpha_mask_filter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(rtc_scene, geometry);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    device.check("committing the triangle geometry");
}

RTCBuildQuality rtc_build_quality(EmbreeBuildQuality quality) {
    switch (quality) {
        case EmbreeBuildQuality::low: return RTC_BUILD_QUALITY_LOW;
        case EmbreeBuildQuality::medium: return RTC_BUILD_QUALITY_MEDIUM;
        case EmbreeBuildQuality::high: return RTC_BUILD_QUALITY_HIGH;
    }
    return RTC_BUILD_QUALITY_MEDIUM;
}

unsigned resolve_thread_count(int requested) {
    if (requested > 0) return static_cast<unsigned>(requested);
    return std::max(1u, std::thread::hardware_concurrency());
}

// Fills the BVH of `rtc_scene` with the scene's moving triangles, with the
// options' scene flags and build quality.
void build_scene(Device& device, const SceneHandle& rtc_scene, const Scene& scene, const CameraModel& model,
                 const SurfaceShader& shader, const EmbreeOptions& options) {
    rtcSetSceneFlags(rtc_scene.get(), options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(rtc_scene.get(), rtc_build_quality(options.build_quality));
    add_moving_mesh(device, rtc_scene.get(), scene, model, shader);
    rtcCommitScene(rtc_scene.get());
    device.check("building the BVH");
}

// The primary rays of the image, a row at a time: rows are handed out
// dynamically, each pixel's samples are summed in a fixed order by one
// thread, so the image does not depend on the schedule.
class RowTracer {
public:
    RowTracer(RTCScene rtc_scene, const Scene& scene, const CameraModel& model, const SurfaceShader& shader,
              const RenderSettings& settings, const EmbreeOptions& options, Image& image,
              RenderClock::time_point start)
        : rtc_scene_(rtc_scene), scene_(scene), model_(model), shader_(shader), settings_(settings),
          options_(options), image_(image), start_(start),
          bounces_(options.secondary == EmbreeSecondary::bounce && has_specular_material(scene)) {}

    // Traces rows until none is left; one caller reports progress.
    void run(bool reports_progress) {
        const int width = settings_.width;
        const auto spp = static_cast<std::uint32_t>(settings_.spp);
        PrimaryRayTracer tracer(rtc_scene_, options_.tracing);
        SecondaryTracer secondary(rtc_scene_, scene_, model_, shader_.flat_colours());
        std::vector<PrimaryRay> rays(static_cast<std::size_t>(width) * spp);
        std::vector<RowSample> samples(rays.size());
        std::vector<std::uint32_t> prim_ids(rays.size());
        std::vector<kernelf::PixelSample> pixel_buffer(spp);
        tracer.set_filter_data(samples.data());
        std::uint64_t hits = 0;
        int last_percent = -1;
        for (int py = next_row_.fetch_add(1); py < settings_.height; py = next_row_.fetch_add(1)) {
            make_row_rays(py, rays, samples, pixel_buffer);
            tracer.trace(rays.data(), rays.size(), prim_ids.data());
            hits += sum_row(py, rays, prim_ids, samples, secondary);
            const int done = rows_done_.fetch_add(1) + 1;
            if (reports_progress && ms_since(start_) > 1000.0) {
                const int percent = static_cast<int>(100LL * done / settings_.height);
                if (percent != last_percent) {
                    std::fprintf(stderr, "\rembree: %3d%%", percent);
                    std::fflush(stderr);
                    last_percent = percent;
                    progress_shown_ = true;
                }
            }
        }
        hits_.fetch_add(hits);
        secondary_rays_.fetch_add(secondary.rays_traced());
    }

    // After a failed thread start: the started helpers stop early.
    void stop() { next_row_.store(settings_.height); }
    bool progress_shown() const { return progress_shown_; }
    std::uint64_t hits() const { return hits_.load(); }
    std::uint64_t secondary_rays() const { return secondary_rays_.load(); }

private:
    // Row py's rays and their samples, pixel by pixel in sample order
    // (pixel_buffer: one pixel's samples, scratch).
    void make_row_rays(int py, std::vector<PrimaryRay>& rays, std::vector<RowSample>& samples,
                       std::vector<kernelf::PixelSample>& pixel_buffer) const {
        const auto spp = static_cast<std::uint32_t>(settings_.spp);
        for (int px = 0; px < settings_.width; ++px) {
            const patternsf::SamplerSetup pattern = patternsf::sampler_setup(
                settings_.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), spp, settings_.seed);
            pixel_samples(pattern, 0, spp, pixel_buffer.data(), lens_samples_for(model_.lens_radius));
            for (std::uint32_t j = 0; j < spp; ++j) {
                const kernelf::PixelSample& sample = pixel_buffer[j];
                const glm::vec2 ndc = model_.sample_ndc(px, py, sample.offset);
                const Ray ray = model_.lens_ray(ndc, sample.lens);
                samples[static_cast<std::size_t>(px) * spp + j] = RowSample{ndc, sample.lens, sample.time};
                rays[static_cast<std::size_t>(px) * spp + j] =
                    PrimaryRay{ray.origin.x,    ray.origin.y,    ray.origin.z,    ray.t_near,
                               ray.direction.x, ray.direction.y, ray.direction.z, sample.time};
            }
        }
    }

    // Row py's pixels: the sum of their samples' colours; returns the hits.
    // With bouncing on, a sample whose triangle is a mirror or dielectric
    // gets the colour of its bounce instead of its surface's colour.
    std::uint64_t sum_row(int py, const std::vector<PrimaryRay>& rays, const std::vector<std::uint32_t>& prim_ids,
                          const std::vector<RowSample>& samples, SecondaryTracer& secondary) {
        const auto spp = static_cast<std::uint32_t>(settings_.spp);
        std::uint64_t hits = 0;
        for (int px = 0; px < settings_.width; ++px) {
            const std::uint64_t hits_before = hits;
            glm::vec3 sum(0.0f);
            for (std::uint32_t j = 0; j < spp; ++j) {
                const std::size_t k = static_cast<std::size_t>(px) * spp + j;
                const std::uint32_t id = prim_ids[k];
                static_assert(no_primitive == SurfaceShader::no_hit, "one id for no hit");
                if (id != no_primitive && bounces_ && is_specular(id)) {
                    const PrimaryRay& ray = rays[k];
                    sum += secondary.bounce({ray.org_x, ray.org_y, ray.org_z}, {ray.dir_x, ray.dir_y, ray.dir_z},
                                            ray.time, id);
                } else {
                    sum += shader_.sample_colour(id, samples[k].ndc, samples[k].lens, samples[k].time);
                }
                if (id != no_primitive) ++hits;
            }
            image_.at(px, py) = sum;
            image_.coverage[image_.index(px, py)] =
                resolve_coverage(static_cast<std::uint32_t>(hits - hits_before), settings_.spp);
        }
        return hits;
    }

    bool is_specular(std::uint32_t triangle) const {
        return scene_.materials[scene_.triangle_material[triangle]].kind != MaterialKind::diffuse;
    }

    RTCScene rtc_scene_;
    const Scene& scene_;
    const CameraModel& model_;
    const SurfaceShader& shader_;
    const RenderSettings& settings_;
    const EmbreeOptions& options_;
    Image& image_;
    RenderClock::time_point start_;
    std::atomic<int> next_row_{0};
    std::atomic<int> rows_done_{0};
    std::atomic<std::uint64_t> hits_{0};
    std::atomic<std::uint64_t> secondary_rays_{0};
    bool progress_shown_ = false;
    bool bounces_;
};

// Runs `tracer` on thread_count threads (the caller's among them).
void trace_on_threads(RowTracer& tracer, unsigned thread_count, int height, bool progress) {
    std::vector<std::thread> helpers;
    try {
        for (unsigned i = 1; i < std::min<unsigned>(thread_count, static_cast<unsigned>(height)); ++i) {
            helpers.emplace_back([&tracer] { tracer.run(false); });
        }
    } catch (...) {
        tracer.stop();
        for (std::thread& helper : helpers) helper.join();
        throw;
    }
    tracer.run(progress);
    for (std::thread& helper : helpers) helper.join();
    if (tracer.progress_shown()) std::fprintf(stderr, "\rembree: 100%%\n");
}

}  // namespace

RenderResult render_embree(const Scene& scene, const RenderSettings& settings, const EmbreeOptions& options) {
    const Clock::time_point start = Clock::now();
    validate_settings(settings);
    const RenderMethodInfo& method = render_method_info(settings.method);
    if (!takes(method.backends, Backend::embree)) {
        throw std::invalid_argument(std::string("render method ") + method.name + ": " +
                                    only_backends_take_it(method.backends) + " (backend embree)");
    }
    require_valid_scene(scene);
    const CameraModel model(scene.camera, settings.width, settings.height);
    const unsigned thread_count = resolve_thread_count(settings.threads);

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = scene.triangles.size();

    Clock::time_point phase_start = Clock::now();
    const SurfaceShader shader(scene, model, static_cast<int>(thread_count));
    stats.ms_per_phase.emplace_back("shade", ms_since(phase_start));

    phase_start = Clock::now();
    Device device(thread_count);
    SceneHandle rtc_scene(rtcNewScene(device.get()));
    device.check("creating the scene");
    build_scene(device, rtc_scene, scene, model, shader, options);
    stats.ms_per_phase.emplace_back("build BVH", ms_since(phase_start));

    phase_start = Clock::now();
    result.image = Image(settings.width, settings.height);
    result.image.coverage.resize(result.image.pixels.size());
    RowTracer tracer(rtc_scene.get(), scene, model, shader, settings, options, result.image, start);
    trace_on_threads(tracer, thread_count, settings.height, settings.progress);
    device.check("tracing");
    stats.ms_per_phase.emplace_back("trace", ms_since(phase_start));

    phase_start = Clock::now();
    for (glm::vec3& pixel : result.image.pixels) pixel = resolve_box(pixel, settings.spp);
    stats.ms_per_phase.emplace_back("resolve", ms_since(phase_start));

    stats.samples_tested = static_cast<std::uint64_t>(settings.width) * static_cast<std::uint64_t>(settings.height) *
                           static_cast<std::uint64_t>(settings.spp);
    stats.samples_hit = tracer.hits();
    stats.secondary_rays = tracer.secondary_rays();
    if (has_specular_material(scene) && scene.environment == BC_ENVIRONMENT_NONE) {
        result.warnings.push_back("embree: scene '" + scene.name +
                                  "' has mirrors or dielectrics but no environment: rays that leave the scene "
                                  "get the background colour");
    }
    stats.ms_total = ms_since(start);
    return result;
}

}  // namespace blurcull::frontend
