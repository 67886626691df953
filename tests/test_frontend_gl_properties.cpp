// The GPU-side property test (issue 22, item 2): the property generators'
// triangles and samples (every family of kernel_generators.hpp) are uploaded,
// and a compute shader evaluates ENTIRELY in GLSL, with the emitted kernel
// library (bc_* names), the exact test bc_covers and every cull's bounds and
// tests that a backend uses:
//   - the screen bound (box and hull edges): bc_screen_contains,
//   - bc_sample_bounds over the footprint: bc_sample_passes and bc_sample_passes_at,
//   - bc_sample_bounds_in_tile on the quarter of the footprint holding the
//     sample, the footprint as its tile (the tile planes): bc_sample_passes_at,
//   - bc_stratum_screen_box of the sample's stratum (4 time slices by lens
//     halves in u and v, the CPU backend's kind of strata), narrowing each
//     method's screen bound,
//   - bc_depth_floor of the sample's time slice (bc_depth_floor_scale over the
//     whole shutter and lens): a covered sample's depth must not lie below it,
// for all six cull methods (BC_CULL_*). Atomics count, per family, the
// covered samples and, per method and test, the covered samples that test
// culls (false culls): the GPU's bounds judged against the GPU's own covers,
// so whatever arithmetic the GPU has (docs/glsl.md's model), the count must
// be 0. Each false cull is judged on the host by the double covers on the
// same float inputs, and counted apart: those it accepts too (the triangle
// really covers the sample) and those covered by the GPU's float rounding
// only. Both are asserted 0 (docs/kernel.md, "Under the GPU arithmetic
// model").
//
// Size: BLURCULL_GPU_PROPERTY_SAMPLES=N asks for N covered samples per method
// in all (each covered sample is judged by every method and test); default
// 200000 times BLURCULL_PROPERTY_SCALE (about a minute on llvmpipe, 2 cores).
// The work goes out in batches of configurations, each dispatch sized to run
// about 0.25 s (never over ~1 s: GPU watchdogs), the counters read back per
// batch. On a GPU: BLURCULL_GPU_PROPERTY_SAMPLES=10000000 test_frontend_gl_properties
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.

#include "gl_parity_helpers.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;
using namespace blurcull::frontend::test;

namespace {

constexpr int kSamplesPerConfig = 192;  // as the host property test
constexpr int kConfigFloats = 36;
constexpr int kSampleFloats = 5;
constexpr int kMethods = method_count;
constexpr int kKinds = 5;
const char* const kKindNames[kKinds] = {"screen_contains", "sample_passes", "sample_passes_at", "in_tile",
                                        "stratum_box"};
// Counter layout (uints), per batch (one family):
constexpr int kSamplesAt = 0;
constexpr int kCoveredAt = 1;
constexpr int kFloorBelowAt = 2;   // covered samples whose depth lies below their depth floor
constexpr int kFlooredAt = 3;      // covered samples with a floor above 0 (the floor was tested)
constexpr int kFalseCullsAt = 4;   // kMethods * kKinds
constexpr int kCulledAt = kFalseCullsAt + kMethods * kKinds;  // per method: samples culled by screen && passes_at
constexpr int kFirstBadAt = kCulledAt + kMethods;             // (sample index) * 64 + code, atomicMin
constexpr int kCounters = kFirstBadAt + 1;
constexpr int kFloorCode = kMethods * kKinds;  // the code of a depth-floor failure

const char* const kPropertyMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Configs { float config_in[]; };
layout(std430, binding = 1) readonly buffer Samples { float sample_in[]; };
layout(std430, binding = 2) buffer Counters { uint counters[]; };
layout(std430, binding = 3) writeonly buffer CulledCovered { uint culled_covered[]; };  // per sample: bit m, method m
uniform uint config_count;

const int CONFIG_FLOATS = 36;
const int SAMPLE_FLOATS = 5;
const int SAMPLES = 192;
const int METHODS = 6;
const int KINDS = 5;
const int SAMPLES_AT = 0;
const int COVERED_AT = 1;
const int FLOOR_BELOW_AT = 2;
const int FLOORED_AT = 3;
const int FALSE_CULLS_AT = 4;
const int CULLED_AT = FALSE_CULLS_AT + METHODS * KINDS;
const int FIRST_BAD_AT = CULLED_AT + METHODS;
const int COUNTERS = FIRST_BAD_AT + 1;
const int STRATA = 16;  // 4 time slices by u halves by v halves

shared MovingTriangle tri;
shared ScreenBound screen[METHODS];
shared SampleBounds bounds[METHODS];
shared SampleBounds quarter[METHODS * 4];
shared vec4 strata[METHODS * STRATA];
shared float floors[4];
shared uint counts[COUNTERS];

// Part k of [lo, hi] cut into 1 / inv_parts equal parts (a power of two):
// exact ends, and no division (a GPU's may be inexact, docs/glsl.md).
vec2 slice(int k, float inv_parts, float lo, float hi) {
    float step = (hi - lo) * inv_parts;
    return vec2(lo + step * float(k), lo + step * float(k + 1));
}

void fail(uint index, int code) {
    atomicMin(counts[FIRST_BAD_AT], index * 64u + uint(code));
}

void main() {
    uint config = gl_WorkGroupID.x;
    int lid = int(gl_LocalInvocationID.x);
    int c = int(config) * CONFIG_FLOATS;
    for (int k = lid; k < COUNTERS; k += 64) counts[k] = k == FIRST_BAD_AT ? 0xffffffffu : 0u;
    if (lid == 0) {
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = vec3(config_in[c + 3 * j], config_in[c + 3 * j + 1], config_in[c + 3 * j + 2]);
            tri.c[j] = vec2(config_in[c + 18 + 2 * j], config_in[c + 19 + 2 * j]);
        }
    }
    float near = config_in[c + 30];
    vec2 lo = vec2(config_in[c + 31], config_in[c + 32]);
    vec2 hi = vec2(config_in[c + 33], config_in[c + 34]);
    vec2 mid = lo + (hi - lo) * 0.5;
    barrier();
    if (lid < METHODS) {
        screen[lid] = bc_screen_bound(tri, near, lid);
        bounds[lid] = bc_sample_bounds(tri, lo, hi, lid);
    }
    if (lid == 63) {
        float extent = max(max(1.0, max(abs(lo.x), abs(lo.y))), max(abs(hi.x), abs(hi.y)));
        float scale = bc_depth_floor_scale(tri, vec2(0.0, 1.0), vec2(-1.0, 1.0), vec2(-1.0, 1.0), extent);
        for (int k = 0; k < 4; ++k) floors[k] = bc_depth_floor(tri, slice(k, 0.25, 0.0, 1.0), scale);
    }
    barrier();
    for (int k = lid; k < METHODS * 4 + METHODS * STRATA; k += 64) {
        if (k < METHODS * 4) {
            int m = k / 4;
            int q = k % 4;
            vec2 q_lo = vec2((q & 1) == 0 ? lo.x : mid.x, (q & 2) == 0 ? lo.y : mid.y);
            vec2 q_hi = vec2((q & 1) == 0 ? mid.x : hi.x, (q & 2) == 0 ? mid.y : hi.y);
            quarter[k] = bc_sample_bounds_in_tile(tri, q_lo, q_hi, m, bounds[m]);
        } else {
            int n = k - METHODS * 4;
            int m = n / STRATA;
            int st = n % STRATA;
            strata[n] = bc_stratum_screen_box(tri, near, screen[m], slice(st / 4, 0.25, 0.0, 1.0),
                                              slice(st % 2, 0.5, -1.0, 1.0), slice((st / 2) % 2, 0.5, -1.0, 1.0));
        }
    }
    barrier();
    for (int n = lid; n < SAMPLES; n += 64) {
        uint index = config * uint(SAMPLES) + uint(n);
        int i = int(index) * SAMPLE_FLOATS;
        vec2 s = vec2(sample_in[i], sample_in[i + 1]);
        vec2 uv = vec2(sample_in[i + 2], sample_in[i + 3]);
        float t = sample_in[i + 4];
        int slice_t = min(int(t * 4.0), 3);
        int st = slice_t * 4 + ((uv.y >= 0.0) ? 2 : 0) + ((uv.x >= 0.0) ? 1 : 0);
        int q = (s.x <= mid.x ? 0 : 1) + (s.y <= mid.y ? 0 : 2);
        float depth;
        bool covered = bc_covers(tri, s, uv, t, near, depth);
        atomicAdd(counts[SAMPLES_AT], 1u);
        if (covered) {
            atomicAdd(counts[COVERED_AT], 1u);
            if (floors[slice_t] > 0.0) atomicAdd(counts[FLOORED_AT], 1u);
            if (depth < floors[slice_t]) {
                atomicAdd(counts[FLOOR_BELOW_AT], 1u);
                fail(index, METHODS * KINDS);
            }
        }
        uint culled_methods = 0u;
        for (int m = 0; m < METHODS; ++m) {
            bool pass[KINDS];
            pass[0] = bc_screen_contains(screen[m], s);
            pass[1] = bc_sample_passes(bounds[m], uv, t);
            pass[2] = bc_sample_passes_at(bounds[m], s, uv, t);
            pass[3] = bc_sample_passes_at(quarter[m * 4 + q], s, uv, t);
            vec4 box = strata[m * STRATA + st];
            pass[4] = s.x >= box.x && s.x <= box.z && s.y >= box.y && s.y <= box.w;
            if (!(pass[0] && pass[2])) atomicAdd(counts[CULLED_AT + m], 1u);
            if (!covered) continue;
            for (int k = 0; k < KINDS; ++k) {
                if (!pass[k]) {
                    atomicAdd(counts[FALSE_CULLS_AT + m * KINDS + k], 1u);
                    fail(index, m * KINDS + k);
                    culled_methods |= 1u << uint(m);
                }
            }
        }
        culled_covered[index] = culled_methods;
    }
    barrier();
    for (int k = lid; k < COUNTERS; k += 64) {
        if (k == FIRST_BAD_AT) atomicMin(counters[k], counts[k]);
        else if (counts[k] != 0u) atomicAdd(counters[k], counts[k]);
    }
}
)glsl";

struct Tally {
    std::uint64_t configs = 0, samples = 0, covered = 0, floor_below = 0, floored = 0;
    std::array<std::uint64_t, kMethods * kKinds> false_culls{};
    std::array<std::uint64_t, kMethods> culled{};
    // Of the false culls, per method: samples the double covers on the same
    // float inputs accepts too, and samples covered by float rounding only
    // (with the largest |s| among them).
    std::array<std::uint64_t, kMethods> exact_culls{}, rounding_culls{};
    double rounding_cull_reach = 0.0;
    std::string first_bad;  // the first false cull found, described

    void add(const Tally& o) {
        configs += o.configs;
        samples += o.samples;
        covered += o.covered;
        floor_below += o.floor_below;
        floored += o.floored;
        for (std::size_t k = 0; k < false_culls.size(); ++k) false_culls[k] += o.false_culls[k];
        for (std::size_t k = 0; k < culled.size(); ++k) culled[k] += o.culled[k];
        for (std::size_t k = 0; k < exact_culls.size(); ++k) exact_culls[k] += o.exact_culls[k];
        for (std::size_t k = 0; k < rounding_culls.size(); ++k) rounding_culls[k] += o.rounding_culls[k];
        rounding_cull_reach = std::max(rounding_cull_reach, o.rounding_cull_reach);
        if (first_bad.empty()) first_bad = o.first_bad;
    }
    std::uint64_t method_false_culls(int m) const {
        std::uint64_t n = 0;
        for (int k = 0; k < kKinds; ++k) n += false_culls[static_cast<std::size_t>(m * kKinds + k)];
        return n;
    }
};

std::uint64_t env_count(const char* name, std::uint64_t fallback) {
    const char* env = std::getenv(name);
    if (!env || !*env) return fallback;
    double v = std::atof(env);
    return v >= 1.0 ? static_cast<std::uint64_t>(v) : fallback;
}

class Runner {
public:
    explicit Runner(const gl::HeadlessContext& context)
        : f_(context.gl()), program_(f_, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), kPropertyMain}}}) {}

    // Runs configurations of `family` from `rng` until `covered_target`
    // covered samples or `max_configs` configurations.
    Tally run(Family family, Rng& rng, std::uint64_t covered_target, std::uint64_t max_configs) {
        Tally tally;
        while (tally.covered < covered_target && tally.configs < max_configs) {
            auto count = static_cast<int>(std::min<std::uint64_t>(static_cast<std::uint64_t>(batch_), max_configs - tally.configs));
            Tally part = run_batch(family, rng, count);
            tally.add(part);
        }
        return tally;
    }

    double gpu_seconds() const { return gpu_seconds_; }
    double host_seconds() const { return host_seconds_; }
    double longest_dispatch_ms() const { return longest_ms_; }
    int dispatches() const { return dispatches_; }

private:
    Tally run_batch(Family family, Rng& rng, int count) {
        auto host_start = std::chrono::steady_clock::now();
        std::vector<Config> cfgs;
        cfgs.reserve(static_cast<std::size_t>(count));
        std::vector<float> configs;
        std::vector<float> samples;
        configs.reserve(static_cast<std::size_t>(count) * kConfigFloats);
        samples.reserve(static_cast<std::size_t>(count) * kSamplesPerConfig * kSampleFloats);
        for (int n = 0; n < count; ++n) {
            Config cfg = make_config(rng, family);
            kernel<float>::MovingTriangle tri = to_real<float>(cfg.tri);
            for (int j = 0; j < 6; ++j)
                for (int a = 0; a < 3; ++a) configs.push_back(tri.p[j][a]);
            for (int j = 0; j < 6; ++j)
                for (int a = 0; a < 2; ++a) configs.push_back(tri.c[j][a]);
            const glm::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
            configs.insert(configs.end(), {static_cast<float>(cfg.near), lo.x, lo.y, hi.x, hi.y, 0.0f});
            for (int k = 0; k < kSamplesPerConfig; ++k) {
                Sample5 smp = make_sample(rng, cfg);
                // As the host property test: the position rounded, then kept in the footprint.
                const glm::vec2 s = glm::clamp(glm::vec2(smp.s), lo, hi);
                samples.insert(samples.end(), {s.x, s.y, static_cast<float>(smp.uv.x), static_cast<float>(smp.uv.y),
                                               static_cast<float>(smp.t)});
            }
            cfgs.push_back(cfg);
        }
        host_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - host_start).count();

        auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
        gl::Buffer config_buffer(f_, GL_SHADER_STORAGE_BUFFER, bytes(configs), configs.data());
        gl::Buffer sample_buffer(f_, GL_SHADER_STORAGE_BUFFER, bytes(samples), samples.data());
        std::array<std::uint32_t, kCounters> counters{};
        counters[kFirstBadAt] = 0xffffffffu;
        gl::Buffer counter_buffer(f_, GL_SHADER_STORAGE_BUFFER, sizeof counters, counters.data());
        std::vector<std::uint32_t> culled_covered(samples.size() / kSampleFloats, 0u);
        gl::Buffer culled_buffer(f_, GL_SHADER_STORAGE_BUFFER, bytes(culled_covered), culled_covered.data());
        config_buffer.bind_base(0);
        sample_buffer.bind_base(1);
        counter_buffer.bind_base(2);
        culled_buffer.bind_base(3);
        f_.UseProgram(program_.id());
        f_.Uniform1ui(f_.GetUniformLocation(program_.id(), "config_count"), static_cast<GLuint>(count));
        auto start = std::chrono::steady_clock::now();
        f_.DispatchCompute(static_cast<GLuint>(count), 1, 1);
        f_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        f_.Finish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        gl::check_gl(f_, "running the property shader");
        counter_buffer.read(counters.data(), sizeof counters);
        culled_buffer.read(culled_covered.data(), bytes(culled_covered));
        f_.UseProgram(0);
        gpu_seconds_ += ms / 1000.0;
        longest_ms_ = std::max(longest_ms_, ms);
        ++dispatches_;
        // The next batch: about 250 ms of work, at most twice this one's size.
        if (ms < 125.0) batch_ = std::min(batch_ * 2, kMaxBatch);
        else if (ms > 500.0) batch_ = std::max(batch_ / 2, 16);

        Tally t;
        t.configs = static_cast<std::uint64_t>(count);
        t.samples = counters[kSamplesAt];
        t.covered = counters[kCoveredAt];
        t.floor_below = counters[kFloorBelowAt];
        t.floored = counters[kFlooredAt];
        for (int k = 0; k < kMethods * kKinds; ++k) t.false_culls[static_cast<std::size_t>(k)] = counters[kFalseCullsAt + k];
        for (int m = 0; m < kMethods; ++m) t.culled[static_cast<std::size_t>(m)] = counters[kCulledAt + m];
        if (counters[kFirstBadAt] != 0xffffffffu) t.first_bad = describe(cfgs, samples, counters[kFirstBadAt], family);
        classify_false_culls(cfgs, samples, culled_covered, t);
        return t;
    }

    // Each false cull judged on the host by the double covers on the same
    // float inputs: accepted there too (a real false cull), or covered by
    // the GPU's float rounding only.
    static void classify_false_culls(const std::vector<Config>& cfgs, const std::vector<float>& samples,
                                     const std::vector<std::uint32_t>& culled_covered, Tally& t) {
        using Kd = kernel<double>;
        for (std::size_t index = 0; index < culled_covered.size(); ++index) {
            const std::uint32_t methods = culled_covered[index];
            if (methods == 0u) continue;
            const Config& cfg = cfgs[index / kSamplesPerConfig];
            const kernel<float>::MovingTriangle tri_f = to_real<float>(cfg.tri);
            Kd::MovingTriangle tri;
            for (int j = 0; j < 6; ++j) {
                tri.p[j] = Kd::vec3(tri_f.p[j]);
                tri.c[j] = Kd::vec2(tri_f.c[j]);
            }
            const float* smp = &samples[index * kSampleFloats];
            double depth = 0.0;
            const bool exact = Kd::covers(tri, Kd::vec2(smp[0], smp[1]), Kd::vec2(smp[2], smp[3]), double(smp[4]),
                                          double(static_cast<float>(cfg.near)), depth);
            for (int m = 0; m < kMethods; ++m) {
                if (!(methods & (1u << m))) continue;
                if (exact) ++t.exact_culls[static_cast<std::size_t>(m)];
                else ++t.rounding_culls[static_cast<std::size_t>(m)];
            }
            if (!exact)
                t.rounding_cull_reach = std::max({t.rounding_cull_reach, double(std::abs(smp[0])), double(std::abs(smp[1]))});
        }
    }

    static std::string describe(const std::vector<Config>& cfgs, const std::vector<float>& samples, std::uint32_t code,
                                Family family) {
        std::uint32_t index = code / 64u;
        int what = static_cast<int>(code % 64u);
        const Config& cfg = cfgs[index / kSamplesPerConfig];
        const kernel<float>::MovingTriangle tri = to_real<float>(cfg.tri);
        const float* s = &samples[static_cast<std::size_t>(index) * kSampleFloats];
        std::string text = std::string("family ") + family_name(family) + ", " +
                           (what == kFloorCode ? std::string("depth floor")
                                               : std::string(method_name(what / kKinds)) + " " + kKindNames[what % kKinds]);
        char line[200];
        for (int j = 0; j < 6; ++j) {
            std::snprintf(line, sizeof line, "\n  p[%d] = (%a, %a, %a) c = (%a, %a)", j, double(tri.p[j].x),
                          double(tri.p[j].y), double(tri.p[j].z), double(tri.c[j].x), double(tri.c[j].y));
            text += line;
        }
        std::snprintf(line, sizeof line, "\n  near %a footprint (%a, %a)-(%a, %a)", double(float(cfg.near)),
                      double(float(cfg.s_lo.x)), double(float(cfg.s_lo.y)), double(float(cfg.s_hi.x)),
                      double(float(cfg.s_hi.y)));
        text += line;
        std::snprintf(line, sizeof line, "\n  sample s (%a, %a) uv (%a, %a) t %a", double(s[0]), double(s[1]),
                      double(s[2]), double(s[3]), double(s[4]));
        return text + line;
    }

    static constexpr int kMaxBatch = 16384;  // 3.1 M samples, 63 MB of samples per dispatch
    const gl::Functions& f_;
    gl::Program program_;
    int batch_ = 32;
    double gpu_seconds_ = 0.0, host_seconds_ = 0.0, longest_ms_ = 0.0;
    int dispatches_ = 0;
};

void print_row(const char* family, const Tally& t) {
    std::printf("%-14s %9" PRIu64 " configs %11" PRIu64 " samples %11" PRIu64 " covered", family, t.configs, t.samples,
                t.covered);
    for (int m = 0; m < kMethods; ++m)
        std::printf(" | %s %" PRIu64 " fc, %.1f%% culled", method_name(m), t.method_false_culls(m),
                    t.samples ? 100.0 * double(t.culled[static_cast<std::size_t>(m)]) / double(t.samples) : 0.0);
    std::printf(" | depth floor %" PRIu64 " below (%" PRIu64 " floored)\n", t.floor_below, t.floored);
}

}  // namespace

TEST_CASE("GPU-side property: no cull's GLSL bounds cull a sample the GLSL covers accepts") {
    auto context = context_or_skip();
    if (!context) return;
    const std::uint64_t target = env_count("BLURCULL_GPU_PROPERTY_SAMPLES",
                                           static_cast<std::uint64_t>(200000.0 * property_scale()));
    std::printf("GL_RENDERER: %s, GL_VERSION: %s (%s)\n", context->renderer().c_str(), context->version().c_str(),
                gl::context_kind_name(context->kind()));
    std::printf("target: %" PRIu64 " covered samples per method (BLURCULL_GPU_PROPERTY_SAMPLES)\n", target);
    std::fflush(stdout);
    auto start = std::chrono::steady_clock::now();
    Runner runner(*context);
    const std::vector<Family> families = all_families();
    // Each family a twelfth; families that rarely cover stop at their cap,
    // and the motion, defocus and both families make up the rest.
    const std::uint64_t share = target / families.size() + 1;
    Tally total;
    std::array<Tally, 12> per_family;
    std::uint64_t seed = 0x6b0e0000;
    for (std::size_t f = 0; f < families.size(); ++f) {
        Rng rng(seed + f);
        per_family[f] = runner.run(families[f], rng, share, share / 4 + 64);
        total.add(per_family[f]);
    }
    for (std::size_t f = 0; total.covered < target; f = (f + 1) % 3) {
        Rng rng(seed + 0x100 + f + total.configs);
        Tally more = runner.run(families[f], rng, std::min<std::uint64_t>(target - total.covered, share),
                                (target - total.covered) / 4 + 64);
        per_family[f].add(more);
        total.add(more);
    }
    for (std::size_t f = 0; f < families.size(); ++f) print_row(family_name(families[f]), per_family[f]);
    print_row("ALL", total);
    for (int m = 0; m < kMethods; ++m) {
        std::printf("%-10s covered %" PRIu64 ", false culls:", method_name(m), total.covered);
        for (int k = 0; k < kKinds; ++k)
            std::printf(" %s %" PRIu64, kKindNames[k], total.false_culls[static_cast<std::size_t>(m * kKinds + k)]);
        std::printf("\n");
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%d dispatches, longest %.0f ms; GPU %.2f s, host generation %.2f s, wall %.2f s\n",
                runner.dispatches(), runner.longest_dispatch_ms(), runner.gpu_seconds(), runner.host_seconds(), seconds);
    if (!total.first_bad.empty()) std::printf("FALSE CULL: %s\n", total.first_bad.c_str());
    std::fflush(stdout);

    CHECK(total.covered >= target);
    std::printf("false culls of samples covered by float rounding only:");
    for (int m = 0; m < kMethods; ++m)
        std::printf(" %s %" PRIu64, method_name(m), total.rounding_culls[static_cast<std::size_t>(m)]);
    std::printf(", at |s| up to %g\n", total.rounding_cull_reach);
    // No false cull in any family: neither of a sample that the double covers
    // accepts too, nor of one the GPU's float rounding alone covers.
    for (int m = 0; m < kMethods; ++m) {
        const std::string method = method_name(m);
        CAPTURE(method);
        CHECK(total.exact_culls[static_cast<std::size_t>(m)] == 0);
        CHECK(total.rounding_culls[static_cast<std::size_t>(m)] == 0);
    }
    CHECK(total.floor_below == 0);
    // Not vacuous: the floors were tested, and the methods cull.
    CHECK(total.floored > total.covered / 4);
    // (bbox, the screen box alone, culls about 7% of these samples; the others 14 to 82%.)
    for (int m = 0; m < kMethods; ++m) CHECK(total.culled[static_cast<std::size_t>(m)] > total.samples / 20);
    for (std::size_t f = 0; f < families.size(); ++f) {
        const std::string family = family_name(families[f]);
        CAPTURE(family);
        CHECK(per_family[f].covered > 0);
    }
}
