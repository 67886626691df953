// GPU/host parity of the shared kernel: a GLSL 4.50 compute shader built from
// the emitted blurcull_kernel.glsl runs screen_bound + screen_contains,
// sample_bounds + sample_passes (all five methods) + sample_passes_at (edges), covers, classify and
// pixel_sample on host-generated inputs in a headless Mesa context; the host
// runs kernel<float> on the same float inputs. Every decision must agree, every
// bound value within kMaxBoundUlps (docs/glsl.md states the tolerance and the
// measured numbers). That holds where the GL's arithmetic is IEEE-exact
// (probe_arithmetic, gl_parity_helpers.hpp: llvmpipe); on another GPU, or
// with BLURCULL_GL_TOLERANT=1, the comparison asserts instead what
// docs/glsl.md's model lets a GPU differ in (compare_tolerant below).
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.

#include "gl_parity_helpers.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;
using namespace blurcull::frontend::test;
using Kf = kernel<float>;

namespace {

// Tolerances (docs/glsl.md, "Parity"). Decisions: identical. Bound values
// and the covers depth: + - * / min max abs on llvmpipe round like the host,
// so they are expected bit-identical; the tolerance is 0 ULP. The lens
// position of pixel_sample uses the sampler's own division and cos/sin from
// + - * only (sampling_body.inl), bit-identical on any conformant GPU: 0 ULP.
constexpr std::int64_t kMaxBoundUlps = 0;
constexpr std::int64_t kMaxLensUlps = 0;

constexpr int kConfigs = 32768;
constexpr int kSamplesPerConfig = 4;  // 131072 inputs

// Input layout (floats): per config the triangle (p: 18, c: 12), near,
// s_lo, s_hi; per input the sample (s, uv, t) and its pixel-sample key.
constexpr int kConfigFloats = 36;
constexpr int kInputFloats = 5;
constexpr int kInputKeys = 4;  // px, py, index, spp
// Output layout (uints, floats as their bits): per config and method the
// screen bound (empty, lo, hi, hull_count, 24 edges) and sample bounds (empty,
// u_range, v_range, u_time_a, u_time_b, v_time_a, v_time_b), then classify;
// per input the decision bits, the covers depth and the pixel sample (offset,
// lens, time).
constexpr int kScreenUints = 1 + 2 + 2 + 1 + 3 * BC_HULL_MAX;
constexpr int kSampleUints = 1 + 2 + 2 + 4 * 4;
constexpr int kMethods = 6;  // BC_CULL_BBOX .. BC_CULL_HYPERPLANE
constexpr int kConfigUints = kMethods * (kScreenUints + kSampleUints) + 1;
constexpr int kInputUints = 2 + 5;

// The shader's main: the library (blurcull_kernel.glsl) comes before it.
const char* const kParityMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Configs { float config_in[]; };
layout(std430, binding = 1) readonly buffer Inputs { float input_in[]; };
layout(std430, binding = 2) readonly buffer Keys { uint key_in[]; };
layout(std430, binding = 3) writeonly buffer ConfigResults { uint config_out[]; };
layout(std430, binding = 4) writeonly buffer InputResults { uint input_out[]; };
uniform uint input_count;
uniform uint samples_per_config;

const int CONFIG_FLOATS = 36;
const int INPUT_FLOATS = 5;
const int SCREEN_UINTS = 6 + 3 * BC_HULL_MAX;
const int SAMPLE_UINTS = 21;
const int METHODS = 6;
const int CONFIG_UINTS = METHODS * (SCREEN_UINTS + SAMPLE_UINTS) + 1;
const int INPUT_UINTS = 7;

void put(int at, float value) { config_out[at] = floatBitsToUint(value); }

void main() {
    uint id = gl_GlobalInvocationID.x;
    if (id >= input_count) return;
    int config = int(id / samples_per_config);
    int c = config * CONFIG_FLOATS;
    MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = vec3(config_in[c + 3 * j], config_in[c + 3 * j + 1], config_in[c + 3 * j + 2]);
        tri.c[j] = vec2(config_in[c + 18 + 2 * j], config_in[c + 19 + 2 * j]);
    }
    float near = config_in[c + 30];
    vec2 s_lo = vec2(config_in[c + 31], config_in[c + 32]);
    vec2 s_hi = vec2(config_in[c + 33], config_in[c + 34]);
    int i = int(id) * INPUT_FLOATS;
    vec2 s = vec2(input_in[i], input_in[i + 1]);
    vec2 uv = vec2(input_in[i + 2], input_in[i + 3]);
    float t = input_in[i + 4];

    bool first = id % samples_per_config == 0u;
    uint decisions = 0u;
    for (int method = 0; method < METHODS; ++method) {
        ScreenBound sb = bc_screen_bound(tri, near, method);
        SampleBounds b = bc_sample_bounds(tri, s_lo, s_hi, method);
        if (bc_screen_contains(sb, s)) decisions |= 1u << (1 + method);
        if (bc_sample_passes(b, uv, t)) decisions |= 1u << (1 + METHODS + method);
        if (method == BC_CULL_EDGES && bc_sample_passes_at(b, s, uv, t)) decisions |= 1u << (1 + 2 * METHODS);
        if (method == BC_CULL_HYPERPLANE && bc_sample_passes_at(b, s, uv, t)) decisions |= 1u << (2 + 2 * METHODS);
        if (!first) continue;
        int o = config * CONFIG_UINTS + method * (SCREEN_UINTS + SAMPLE_UINTS);
        config_out[o] = sb.empty ? 1u : 0u;
        put(o + 1, sb.lo.x); put(o + 2, sb.lo.y); put(o + 3, sb.hi.x); put(o + 4, sb.hi.y);
        config_out[o + 5] = uint(sb.hull_count);
        for (int k = 0; k < BC_HULL_MAX; ++k) {
            put(o + 6 + 3 * k, sb.hull_edge[k].x);
            put(o + 7 + 3 * k, sb.hull_edge[k].y);
            put(o + 8 + 3 * k, sb.hull_edge[k].z);
        }
        o += SCREEN_UINTS;
        config_out[o] = b.empty ? 1u : 0u;
        put(o + 1, b.u_range.x); put(o + 2, b.u_range.y);
        put(o + 3, b.v_range.x); put(o + 4, b.v_range.y);
        for (int k = 0; k < 4; ++k) {
            put(o + 5 + k, b.u_time_a[k]);
            put(o + 9 + k, b.u_time_b[k]);
            put(o + 13 + k, b.v_time_a[k]);
            put(o + 17 + k, b.v_time_b[k]);
        }
    }
    if (first) config_out[config * CONFIG_UINTS + CONFIG_UINTS - 1] = uint(bc_classify(tri));
    float depth;
    if (bc_covers(tri, s, uv, t, near, depth)) decisions |= 1u;
    int k = int(id) * 4;
    PixelSample ps = bc_pixel_sample(key_in[k], key_in[k + 1], key_in[k + 2], key_in[k + 3], 0x5eedu);
    int o = int(id) * INPUT_UINTS;
    input_out[o] = decisions;
    input_out[o + 1] = floatBitsToUint(depth);
    input_out[o + 2] = floatBitsToUint(ps.offset.x);
    input_out[o + 3] = floatBitsToUint(ps.offset.y);
    input_out[o + 4] = floatBitsToUint(ps.lens.x);
    input_out[o + 5] = floatBitsToUint(ps.lens.y);
    input_out[o + 6] = floatBitsToUint(ps.time);
}
)glsl";

constexpr std::uint32_t kPixelSeed = 0x5eedu;

const char* const kDecisionNames[] = {
    "covers",
    "screen_contains bbox", "screen_contains hull", "screen_contains dualspace", "screen_contains clip2",
    "screen_contains edges", "screen_contains hyperplane",
    "sample_passes bbox", "sample_passes hull", "sample_passes dualspace", "sample_passes clip2",
    "sample_passes edges", "sample_passes hyperplane", "sample_passes_at edges", "sample_passes_at hyperplane"};
constexpr int kDecisionBits = 3 + 2 * kMethods;

// The sample-bound values in output order, two uints per name.
const char* const kSampleFieldNames[] = {"u_range",  "v_range",  "u_time_a", "u_time_a", "u_time_b",
                                         "u_time_b", "v_time_a", "v_time_a", "v_time_b", "v_time_b"};

struct Inputs {
    std::vector<float> configs;
    std::vector<float> samples;
    std::vector<std::uint32_t> keys;
    int config_count = 0;
};

Inputs make_inputs(int config_count, std::uint64_t seed) {
    Inputs in;
    in.config_count = config_count;
    Rng rng(seed);
    std::vector<Family> families = all_families();
    for (int n = 0; n < config_count; ++n) {
        Config cfg = make_config(rng, families[static_cast<std::size_t>(n) % families.size()]);
        Kf::MovingTriangle tri = to_real<float>(cfg.tri);
        for (int j = 0; j < 6; ++j)
            for (int a = 0; a < 3; ++a) in.configs.push_back(tri.p[j][a]);
        for (int j = 0; j < 6; ++j)
            for (int a = 0; a < 2; ++a) in.configs.push_back(tri.c[j][a]);
        in.configs.push_back(static_cast<float>(cfg.near));
        in.configs.push_back(static_cast<float>(cfg.s_lo.x));
        in.configs.push_back(static_cast<float>(cfg.s_lo.y));
        in.configs.push_back(static_cast<float>(cfg.s_hi.x));
        in.configs.push_back(static_cast<float>(cfg.s_hi.y));
        in.configs.push_back(0.0f);  // padding to kConfigFloats
        for (int k = 0; k < kSamplesPerConfig; ++k) {
            Sample5 s = make_sample(rng, cfg);
            in.samples.push_back(static_cast<float>(s.s.x));
            in.samples.push_back(static_cast<float>(s.s.y));
            in.samples.push_back(static_cast<float>(s.uv.x));
            in.samples.push_back(static_cast<float>(s.uv.y));
            in.samples.push_back(static_cast<float>(s.t));
            std::uint32_t spp = 1u + static_cast<std::uint32_t>(rng.below(64));
            in.keys.push_back(static_cast<std::uint32_t>(rng.below(4096)));
            in.keys.push_back(static_cast<std::uint32_t>(rng.below(4096)));
            in.keys.push_back(static_cast<std::uint32_t>(rng.below(static_cast<int>(spp) + 2)));
            in.keys.push_back(spp);
        }
    }
    return in;
}

struct GpuResults {
    std::vector<std::uint32_t> configs;
    std::vector<std::uint32_t> inputs;
    double milliseconds = 0.0;
};

GpuResults run_gpu(const gl::HeadlessContext& context, const Inputs& in) {
    const gl::Functions& f = context.gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), kParityMain}}});
    auto input_count = static_cast<std::uint32_t>(in.config_count * kSamplesPerConfig);
    auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
    gl::Buffer configs(f, GL_SHADER_STORAGE_BUFFER, bytes(in.configs), in.configs.data());
    gl::Buffer samples(f, GL_SHADER_STORAGE_BUFFER, bytes(in.samples), in.samples.data());
    gl::Buffer keys(f, GL_SHADER_STORAGE_BUFFER, bytes(in.keys), in.keys.data());
    GpuResults out;
    out.configs.assign(static_cast<std::size_t>(in.config_count) * kConfigUints, 0u);
    out.inputs.assign(static_cast<std::size_t>(input_count) * kInputUints, 0u);
    gl::Buffer config_results(f, GL_SHADER_STORAGE_BUFFER, bytes(out.configs));
    gl::Buffer input_results(f, GL_SHADER_STORAGE_BUFFER, bytes(out.inputs));
    configs.bind_base(0);
    samples.bind_base(1);
    keys.bind_base(2);
    config_results.bind_base(3);
    input_results.bind_base(4);
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "input_count"), input_count);
    f.Uniform1ui(f.GetUniformLocation(program.id(), "samples_per_config"), kSamplesPerConfig);
    auto start = std::chrono::steady_clock::now();
    f.DispatchCompute((input_count + 63u) / 64u, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gl::check_gl(f, "running the parity shader");
    config_results.read(out.configs.data(), bytes(out.configs));
    input_results.read(out.inputs.data(), bytes(out.inputs));
    f.UseProgram(0);
    return out;
}

// Host results in the GPU's layout.
struct HostResults {
    std::vector<std::uint32_t> configs;
    std::vector<std::uint32_t> inputs;
};

HostResults run_host(const Inputs& in) {
    HostResults out;
    out.configs.assign(static_cast<std::size_t>(in.config_count) * kConfigUints, 0u);
    out.inputs.assign(static_cast<std::size_t>(in.config_count) * kSamplesPerConfig * kInputUints, 0u);
    for (int n = 0; n < in.config_count; ++n) {
        const float* c = &in.configs[static_cast<std::size_t>(n) * kConfigFloats];
        Kf::MovingTriangle tri;
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = Kf::vec3(c[3 * j], c[3 * j + 1], c[3 * j + 2]);
            tri.c[j] = Kf::vec2(c[18 + 2 * j], c[19 + 2 * j]);
        }
        float near = c[30];
        Kf::vec2 s_lo(c[31], c[32]);
        Kf::vec2 s_hi(c[33], c[34]);
        std::uint32_t* co = &out.configs[static_cast<std::size_t>(n) * kConfigUints];
        std::array<Kf::ScreenBound, kMethods> screens;
        std::array<Kf::SampleBounds, kMethods> bounds;
        for (int method = 0; method < kMethods; ++method) {
            const Kf::ScreenBound& sb = screens[static_cast<std::size_t>(method)] = Kf::screen_bound(tri, near, method);
            const Kf::SampleBounds& b = bounds[static_cast<std::size_t>(method)] =
                Kf::sample_bounds(tri, s_lo, s_hi, method);
            std::uint32_t* o = co + method * (kScreenUints + kSampleUints);
            o[0] = sb.empty ? 1u : 0u;
            o[1] = bits_of(sb.lo.x);
            o[2] = bits_of(sb.lo.y);
            o[3] = bits_of(sb.hi.x);
            o[4] = bits_of(sb.hi.y);
            o[5] = static_cast<std::uint32_t>(sb.hull_count);
            for (int k = 0; k < BC_HULL_MAX; ++k)
                for (int a = 0; a < 3; ++a) o[6 + 3 * k + a] = bits_of(sb.hull_edge[k][a]);
            o += kScreenUints;
            o[0] = b.empty ? 1u : 0u;
            o[1] = bits_of(b.u_range.x);
            o[2] = bits_of(b.u_range.y);
            o[3] = bits_of(b.v_range.x);
            o[4] = bits_of(b.v_range.y);
            for (int k = 0; k < 4; ++k) {
                o[5 + k] = bits_of(b.u_time_a[k]);
                o[9 + k] = bits_of(b.u_time_b[k]);
                o[13 + k] = bits_of(b.v_time_a[k]);
                o[17 + k] = bits_of(b.v_time_b[k]);
            }
        }
        co[kConfigUints - 1] = static_cast<std::uint32_t>(Kf::classify(tri));
        for (int k = 0; k < kSamplesPerConfig; ++k) {
            std::size_t id = static_cast<std::size_t>(n) * kSamplesPerConfig + static_cast<std::size_t>(k);
            const float* s = &in.samples[id * kInputFloats];
            Kf::vec2 pos(s[0], s[1]);
            Kf::vec2 uv(s[2], s[3]);
            float t = s[4];
            std::uint32_t decisions = 0u;
            for (int method = 0; method < kMethods; ++method) {
                if (Kf::screen_contains(screens[static_cast<std::size_t>(method)], pos)) decisions |= 1u << (1 + method);
                if (Kf::sample_passes(bounds[static_cast<std::size_t>(method)], uv, t))
                    decisions |= 1u << (1 + kMethods + method);
            }
            if (Kf::sample_passes_at(bounds[BC_CULL_EDGES], pos, uv, t)) decisions |= 1u << (1 + 2 * kMethods);
            if (Kf::sample_passes_at(bounds[BC_CULL_HYPERPLANE], pos, uv, t)) decisions |= 1u << (2 + 2 * kMethods);
            float depth = 0.0f;
            if (Kf::covers(tri, pos, uv, t, near, depth)) decisions |= 1u;
            const std::uint32_t* key = &in.keys[id * kInputKeys];
            Kf::PixelSample ps = Kf::pixel_sample(key[0], key[1], key[2], key[3], kPixelSeed);
            std::uint32_t* io = &out.inputs[id * kInputUints];
            io[0] = decisions;
            io[1] = bits_of(depth);
            io[2] = bits_of(ps.offset.x);
            io[3] = bits_of(ps.offset.y);
            io[4] = bits_of(ps.lens.x);
            io[5] = bits_of(ps.lens.y);
            io[6] = bits_of(ps.time);
        }
    }
    return out;
}

// Every difference between host and GPU, counted and measured.
struct Comparison {
    long decisions = 0;            // decisions compared
    long decision_mismatches = 0;
    std::map<std::string, long> mismatch_by_name;
    long values = 0;               // bound values compared
    std::int64_t max_bound_ulps = 0;
    long bound_values_differing = 0;
    std::int64_t max_depth_ulps = 0;
    std::int64_t max_offset_time_ulps = 0;
    std::int64_t max_lens_ulps = 0;
    std::string first_mismatch;
    std::array<long, kDecisionBits> host_true{};  // per decision bit: how often the host said true
    long inputs = 0;
    std::map<std::string, std::int64_t> max_ulps_by_name;  // values that differ, by field
    std::string worst_value;
};

void note_decision(Comparison& cmp, bool host, bool gpu, const std::string& name, int config) {
    ++cmp.decisions;
    if (host == gpu) return;
    ++cmp.decision_mismatches;
    ++cmp.mismatch_by_name[name];
    if (cmp.first_mismatch.empty())
        cmp.first_mismatch = name + " of config " + std::to_string(config) + ": host " + (host ? "true" : "false") +
                             ", GPU " + (gpu ? "true" : "false");
}

void note_equal(Comparison& cmp, std::uint32_t host, std::uint32_t gpu, const std::string& name, int config) {
    ++cmp.decisions;
    if (host == gpu) return;
    ++cmp.decision_mismatches;
    ++cmp.mismatch_by_name[name];
    if (cmp.first_mismatch.empty())
        cmp.first_mismatch = name + " of config " + std::to_string(config) + ": host " + std::to_string(host) +
                             ", GPU " + std::to_string(gpu);
}

void note_value(Comparison& cmp, std::uint32_t host, std::uint32_t gpu, const std::string& name, int config) {
    ++cmp.values;
    std::int64_t d = ulp_distance(float_of(host), float_of(gpu));
    if (d == 0) return;
    ++cmp.bound_values_differing;
    std::int64_t& worst = cmp.max_ulps_by_name[name];
    worst = std::max(worst, d);
    if (d > cmp.max_bound_ulps) {
        char text[160];
        std::snprintf(text, sizeof text, "%s of config %d: host %.9g, GPU %.9g", name.c_str(), config,
                      static_cast<double>(float_of(host)), static_cast<double>(float_of(gpu)));
        cmp.worst_value = text;
    }
    cmp.max_bound_ulps = std::max(cmp.max_bound_ulps, d);
}

Comparison compare(const Inputs& in, const HostResults& host, const GpuResults& gpu) {
    Comparison cmp;
    const char* methods[] = {"bbox", "hull", "dualspace", "clip2", "edges", "hyperplane"};
    for (int n = 0; n < in.config_count; ++n) {
        const std::uint32_t* h = &host.configs[static_cast<std::size_t>(n) * kConfigUints];
        const std::uint32_t* g = &gpu.configs[static_cast<std::size_t>(n) * kConfigUints];
        for (int method = 0; method < kMethods; ++method) {
            int o = method * (kScreenUints + kSampleUints);
            std::string m = methods[method];
            note_decision(cmp, h[o] != 0u, g[o] != 0u, "screen_bound.empty " + m, n);
            note_equal(cmp, h[o + 5], g[o + 5], "screen_bound.hull_count " + m, n);
            for (int k = 1; k <= 4; ++k) note_value(cmp, h[o + k], g[o + k], "screen_bound.lo/hi " + m, n);
            int edges = static_cast<int>(std::min(h[o + 5], g[o + 5]));
            for (int k = 0; k < 3 * edges; ++k) note_value(cmp, h[o + 6 + k], g[o + 6 + k], "screen_bound.hull_edge " + m, n);
            o += kScreenUints;
            note_decision(cmp, h[o] != 0u, g[o] != 0u, "sample_bounds.empty " + m, n);
            if (h[o] == 0u && g[o] == 0u)
                for (int k = 1; k < kSampleUints; ++k)
                    note_value(cmp, h[o + k], g[o + k], std::string("sample_bounds.") + kSampleFieldNames[(k - 1) / 2] + " " + m, n);
        }
        note_equal(cmp, h[kConfigUints - 1], g[kConfigUints - 1], "classify", n);
        for (int k = 0; k < kSamplesPerConfig; ++k) {
            std::size_t id = static_cast<std::size_t>(n) * kSamplesPerConfig + static_cast<std::size_t>(k);
            const std::uint32_t* hi = &host.inputs[id * kInputUints];
            const std::uint32_t* gi = &gpu.inputs[id * kInputUints];
            ++cmp.inputs;
            for (int bit = 0; bit < kDecisionBits; ++bit) {
                note_decision(cmp, (hi[0] >> bit) & 1u, (gi[0] >> bit) & 1u, kDecisionNames[bit], n);
                cmp.host_true[static_cast<std::size_t>(bit)] += (hi[0] >> bit) & 1u;
            }
            if ((hi[0] & gi[0] & 1u) != 0u)
                cmp.max_depth_ulps = std::max(cmp.max_depth_ulps, ulp_distance(float_of(hi[1]), float_of(gi[1])));
            for (int q : {2, 3, 6})
                cmp.max_offset_time_ulps =
                    std::max(cmp.max_offset_time_ulps, ulp_distance(float_of(hi[q]), float_of(gi[q])));
            for (int q : {4, 5})
                cmp.max_lens_ulps = std::max(cmp.max_lens_ulps, ulp_distance(float_of(hi[q]), float_of(gi[q])));
        }
    }
    return cmp;
}

// The tolerant comparison (a GL whose arithmetic is not IEEE-exact, or
// BLURCULL_GL_TOLERANT): what docs/glsl.md's model lets a GPU differ in.
// - covers: only for samples within kEdgeTolerance of an edge, of det = 0 or
//   of the near plane (covers_condition); its depth, where both cover, within
//   kEdgeTolerance times the depth's condition, plus kDivisionUlps.
// - the culls' decisions (screen_contains, sample_passes, sample_passes_at):
//   a GPU that keeps a sample the host culls is looser, which conservativeness
//   allows (counted); a GPU that culls a sample the host keeps must not cull
//   one that the double oracle covers outside the edge tolerance (whether the
//   GPU's bounds hold against the GPU's own covers is test_frontend_gl_properties).
// - values: the screen box (one division per corner and a margin) within
//   kDivisionUlps ULP of the box's magnitude; hull edges and counts, the
//   sample bounds' ranges and time lines come from hull selection, quadratic
//   roots and cancelling differences (ill-conditioned: a hull edge changed
//   sign on the H200), so their decisions above are compared instead and the
//   values' differences only counted.
// - classify, pixel_sample's offset and time: + - * and comparisons only,
//   identical; its lens position within kMaxLensUlps, as on an exact GL.
struct Tolerant {
    ToleranceTally covers, culls, depth, box, exact;
    long looser = 0;              // GPU kept what the host culled
    long values_differing = 0;    // ill-conditioned values that differ (not asserted)
    std::int64_t max_lens_ulps = 0;
};

Tolerant compare_tolerant(const Inputs& in, const HostResults& host, const GpuResults& gpu) {
    using Kd = kernel<double>;
    Tolerant tol;
    const char* methods[] = {"bbox", "hull", "dualspace", "clip2", "edges", "hyperplane"};
    for (int n = 0; n < in.config_count; ++n) {
        const float* c = &in.configs[static_cast<std::size_t>(n) * kConfigFloats];
        Kf::MovingTriangle tri;
        Kd::MovingTriangle tri_d;
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = Kf::vec3(c[3 * j], c[3 * j + 1], c[3 * j + 2]);
            tri.c[j] = Kf::vec2(c[18 + 2 * j], c[19 + 2 * j]);
            tri_d.p[j] = Kd::vec3(tri.p[j]);
            tri_d.c[j] = Kd::vec2(tri.c[j]);
        }
        const float near = c[30];
        const std::uint32_t* h = &host.configs[static_cast<std::size_t>(n) * kConfigUints];
        const std::uint32_t* g = &gpu.configs[static_cast<std::size_t>(n) * kConfigUints];
        const std::string where = " of config " + std::to_string(n);
        for (int method = 0; method < kMethods; ++method) {
            const int o = method * (kScreenUints + kSampleUints);
            if (h[o] == 0u && g[o] == 0u) {
                double magnitude = 0.0;
                for (int k = 1; k <= 4; ++k) magnitude = std::max(magnitude, double(std::abs(float_of(h[o + k]))));
                const double allowed = kDivisionUlps * std::ldexp(1.0, std::ilogb(std::max(magnitude, 0x1p-126)) - 23);
                for (int k = 1; k <= 4; ++k) {
                    const double d = std::abs(double(float_of(h[o + k])) - double(float_of(g[o + k])));
                    char text[160];
                    std::snprintf(text, sizeof text, "screen_bound.lo/hi %s%s: host %.9g, GPU %.9g (allowed %.3g)",
                                  methods[method], where.c_str(), double(float_of(h[o + k])),
                                  double(float_of(g[o + k])), allowed);
                    if (d != 0.0) tol.box.note(d <= allowed, text);
                }
            }
            tol.values_differing += h[o] != g[o];
            tol.values_differing += h[o + 5] != g[o + 5];
            for (int k = 0; k < 3 * BC_HULL_MAX; ++k) tol.values_differing += h[o + 6 + k] != g[o + 6 + k];
            for (int k = 0; k < kSampleUints; ++k)
                tol.values_differing += h[o + kScreenUints + k] != g[o + kScreenUints + k];
        }
        if (h[kConfigUints - 1] != g[kConfigUints - 1]) tol.exact.note(false, "classify" + where);
        for (int k = 0; k < kSamplesPerConfig; ++k) {
            const std::size_t id = static_cast<std::size_t>(n) * kSamplesPerConfig + static_cast<std::size_t>(k);
            const float* smp = &in.samples[id * kInputFloats];
            const Kf::vec2 s(smp[0], smp[1]), uv(smp[2], smp[3]);
            const float t = smp[4];
            const std::uint32_t* hi = &host.inputs[id * kInputUints];
            const std::uint32_t* gi = &gpu.inputs[id * kInputUints];
            const std::uint32_t differ = hi[0] ^ gi[0];
            if (differ != 0u || (hi[0] & gi[0] & 1u) != 0u) {
                const CoversCondition cond = covers_condition(tri, s, uv, t, near);
                const bool near_edge = cond.margin <= kEdgeTolerance;
                double oracle_depth = 0.0;
                const bool covered = Kd::covers(tri_d, Kd::vec2(s), Kd::vec2(uv), double(t), double(near), oracle_depth);
                char margin[96];
                std::snprintf(margin, sizeof margin, " (margin %.3g, limit %.3g)", cond.margin, kEdgeTolerance);
                if (differ & 1u) tol.covers.note(near_edge, std::string("covers") + where + margin);
                for (int bit = 1; bit < kDecisionBits; ++bit) {
                    if (((differ >> bit) & 1u) == 0u) continue;
                    if ((gi[0] >> bit) & 1u) {
                        ++tol.looser;
                        continue;
                    }
                    tol.culls.note(!covered || near_edge, std::string(kDecisionNames[bit]) + where +
                                                              ": the GPU culls a covered sample the host keeps" + margin);
                }
                if ((hi[0] & gi[0] & 1u) != 0u) {
                    const double hd = float_of(hi[1]), gd = float_of(gi[1]);
                    const double allowed = kEdgeTolerance * cond.depth_condition * std::abs(hd) +
                                           kDivisionUlps * std::ldexp(1.0, std::ilogb(std::max(std::abs(hd), 0x1p-126)) - 23);
                    char text[160];
                    std::snprintf(text, sizeof text, "covers depth%s: host %.9g, GPU %.9g (allowed %.3g)", where.c_str(),
                                  hd, gd, allowed);
                    if (hd != gd) tol.depth.note(std::abs(hd - gd) <= allowed, text);
                }
            }
            for (int q : {2, 3, 6})
                if (hi[q] != gi[q]) tol.exact.note(false, "pixel_sample offset/time" + where);
            for (int q : {4, 5})
                tol.max_lens_ulps = std::max(tol.max_lens_ulps, ulp_distance(float_of(hi[q]), float_of(gi[q])));
        }
    }
    return tol;
}

void report_tally(const std::string& name, const ToleranceTally& t) {
    MESSAGE("  " << name << ": " << t.within << " differ within the model's limit, " << t.outside << " outside"
                 << (t.first_outside.empty() ? std::string() : ", first: " + t.first_outside));
}

void check_parity(const gl::HeadlessContext& context, int config_count, std::uint64_t seed) {
    const ArithmeticProbe probe = probe_arithmetic(context);
    MESSAGE(context.renderer() << ": " << probe.describe());
    Inputs in = make_inputs(config_count, seed);
    GpuResults gpu = run_gpu(context, in);
    HostResults host = run_host(in);
    Comparison cmp = compare(in, host, gpu);
    MESSAGE(std::string(gl::context_kind_name(context.kind()))
            << " (" << context.renderer() << "): " << config_count * kSamplesPerConfig << " inputs, " << config_count
            << " configs, GPU " << gpu.milliseconds << " ms; " << cmp.decisions << " decisions, "
            << cmp.decision_mismatches << " differ; " << cmp.values << " bound values, " << cmp.bound_values_differing
            << " differ, max " << cmp.max_bound_ulps << " ULP; covers depth max " << cmp.max_depth_ulps
            << " ULP; pixel_sample offset/time max " << cmp.max_offset_time_ulps << " ULP, lens max "
            << cmp.max_lens_ulps << " ULP");
    std::string true_counts;
    for (int bit = 0; bit < kDecisionBits; ++bit)
        true_counts += std::string(bit ? ", " : "") + kDecisionNames[bit] + " " + std::to_string(cmp.host_true[static_cast<std::size_t>(bit)]);
    MESSAGE("  true of " << cmp.inputs << " inputs: " << true_counts);
    for (const auto& [name, count] : cmp.mismatch_by_name) MESSAGE("  " << name << ": " << count << " differ");
    for (const auto& [name, ulps] : cmp.max_ulps_by_name) MESSAGE("  " << name << ": max " << ulps << " ULP");
    if (!cmp.worst_value.empty()) MESSAGE("  worst: " << cmp.worst_value);
    if (!probe.tolerant()) {
        // IEEE-exact arithmetic (llvmpipe): host = GLSL bit for bit.
        CHECK_MESSAGE(cmp.decision_mismatches == 0, cmp.first_mismatch);
        CHECK(cmp.max_bound_ulps <= kMaxBoundUlps);
        CHECK(cmp.max_depth_ulps <= kMaxBoundUlps);
        CHECK(cmp.max_offset_time_ulps == 0);
        CHECK(cmp.max_lens_ulps <= kMaxLensUlps);
    } else {
        const Tolerant tol = compare_tolerant(in, host, gpu);
        MESSAGE("tolerant comparison: edge tolerance " << kEdgeTolerance << " of the terms, " << kDivisionUlps
                                                       << " ULP for values through divisions, lens " << kMaxLensUlps
                                                       << " ULP");
        report_tally("covers decisions (within the edge tolerance)", tol.covers);
        report_tally("culls' decisions (GPU tighter: only uncovered or near-edge samples)", tol.culls);
        report_tally("covers depth", tol.depth);
        report_tally("screen box values", tol.box);
        report_tally("exact values (classify, pixel_sample offset/time)", tol.exact);
        MESSAGE("  culls' decisions where the GPU is looser (conservative, allowed): " << tol.looser
                << "; ill-conditioned values that differ (decisions compared instead): " << tol.values_differing
                << "; lens max " << tol.max_lens_ulps << " ULP");
        CHECK_MESSAGE(tol.covers.outside == 0, tol.covers.first_outside);
        CHECK_MESSAGE(tol.culls.outside == 0, tol.culls.first_outside);
        CHECK_MESSAGE(tol.depth.outside == 0, tol.depth.first_outside);
        CHECK_MESSAGE(tol.box.outside == 0, tol.box.first_outside);
        CHECK_MESSAGE(tol.exact.outside == 0, tol.exact.first_outside);
        CHECK(tol.max_lens_ulps <= kMaxLensUlps);
        // On an exact GL forced onto this path, nothing differs at all.
        if (probe.exact) CHECK(cmp.decision_mismatches == 0);
    }
    // The comparison saw real work: bound values, and every per-sample
    // decision taken both ways (bbox and hull never cull by sample_passes).
    CHECK(cmp.values > 100000);
    for (int bit = 0; bit < kDecisionBits; ++bit) {
        CAPTURE(kDecisionNames[bit]);
        long trues = cmp.host_true[static_cast<std::size_t>(bit)];
        CHECK(trues > 0);
        if (bit != 1 + kMethods + BC_CULL_BBOX && bit != 1 + kMethods + BC_CULL_HULL) CHECK(trues < cmp.inputs);
    }
}

}  // namespace

TEST_CASE("the kernel in GLSL decides like the host kernel<float> on 131072 inputs") {
    auto context = context_or_skip();
    if (!context) return;
    check_parity(*context, kConfigs, 0x9a7e5eedull);
}

// The tolerant comparison's own check, no GL needed (an exact GL never
// exercises it with a difference): the host's results as a "GPU" with
// injected differences, one of each kind the model forbids and one it allows.
TEST_CASE("the tolerant comparison accepts what the model allows and flags what it forbids") {
    const Inputs in = make_inputs(2048, 0x70e7a7ceull);
    const HostResults host = run_host(in);
    auto as_gpu = [&] {
        GpuResults g;
        g.configs = host.configs;
        g.inputs = host.inputs;
        return g;
    };
    CHECK(compare_tolerant(in, host, as_gpu()).covers.outside == 0);
    // The sample whose covers decision is farthest from flipping and the one
    // nearest: flipping the first is outside the model, the second (when
    // within the edge tolerance) inside.
    std::size_t far_id = 0, near_id = 0;
    double far_margin = -1.0, near_margin = 1e300;
    long covered_far = -1;
    double covered_far_margin = -1.0;
    for (int n = 0; n < in.config_count; ++n) {
        const float* c = &in.configs[static_cast<std::size_t>(n) * kConfigFloats];
        Kf::MovingTriangle tri;
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = Kf::vec3(c[3 * j], c[3 * j + 1], c[3 * j + 2]);
            tri.c[j] = Kf::vec2(c[18 + 2 * j], c[19 + 2 * j]);
        }
        for (int k = 0; k < kSamplesPerConfig; ++k) {
            const std::size_t id = static_cast<std::size_t>(n) * kSamplesPerConfig + static_cast<std::size_t>(k);
            const float* smp = &in.samples[id * kInputFloats];
            const double m = covers_condition(tri, Kf::vec2(smp[0], smp[1]), Kf::vec2(smp[2], smp[3]), smp[4], c[30]).margin;
            if (m > far_margin) far_margin = m, far_id = id;
            if (m < near_margin) near_margin = m, near_id = id;
            const bool covered = (host.inputs[id * kInputUints] & 1u) != 0u;
            if (covered && m > covered_far_margin) covered_far_margin = m, covered_far = static_cast<long>(id);
        }
    }
    MESSAGE("covers margins: farthest " << far_margin << ", nearest " << near_margin << ", limit " << kEdgeTolerance);
    REQUIRE(far_margin > kEdgeTolerance);
    REQUIRE(covered_far >= 0);
    {
        GpuResults g = as_gpu();
        g.inputs[far_id * kInputUints] ^= 1u;
        const Tolerant t = compare_tolerant(in, host, g);
        CHECK(t.covers.outside == 1);
    }
    if (near_margin <= kEdgeTolerance) {
        GpuResults g = as_gpu();
        g.inputs[near_id * kInputUints] ^= 1u;
        const Tolerant t = compare_tolerant(in, host, g);
        CHECK(t.covers.outside == 0);
        CHECK(t.covers.within == 1);
    }
    {
        // A cull's decision: the GPU culling a covered sample far from every
        // edge is forbidden; the GPU keeping a sample the host culls is allowed.
        const auto id = static_cast<std::size_t>(covered_far);
        const int bit = 1 + BC_CULL_BBOX;  // screen_contains bbox: true for a covered sample
        REQUIRE(((host.inputs[id * kInputUints] >> bit) & 1u) == 1u);
        GpuResults g = as_gpu();
        g.inputs[id * kInputUints] ^= 1u << bit;
        CHECK(compare_tolerant(in, host, g).culls.outside == 1);
    }
    {
        // The screen box: 1 ULP off is within the limit, a tenth of its magnitude is not.
        GpuResults g = as_gpu();
        std::size_t at = 0;
        for (int n = 0; n < in.config_count && at == 0; ++n)
            if (host.configs[static_cast<std::size_t>(n) * kConfigUints] == 0u &&
                std::abs(float_of(host.configs[static_cast<std::size_t>(n) * kConfigUints + 1])) < 10.0f)
                at = static_cast<std::size_t>(n) * kConfigUints + 1;
        REQUIRE(at != 0);
        g.configs[at] = bits_of(std::nextafter(float_of(host.configs[at]), 1e30f));
        Tolerant t = compare_tolerant(in, host, g);
        CHECK(t.box.within == 1);
        CHECK(t.box.outside == 0);
        g.configs[at] = bits_of(float_of(host.configs[at]) * 1.1f + 0.1f);
        t = compare_tolerant(in, host, g);
        CHECK(t.box.outside == 1);
    }
}

TEST_CASE("both headless context kinds run the kernel's GLSL") {
    for (gl::ContextKind kind : {gl::ContextKind::egl_surfaceless, gl::ContextKind::osmesa}) {
        std::string kind_name = gl::context_kind_name(kind);
        CAPTURE(kind_name);
        auto context = context_or_skip(kind);
        if (!context) continue;
        CHECK(context->kind() == kind);
        check_parity(*context, 1024, 0x05e5a11ull + static_cast<unsigned>(kind));
    }
}

TEST_CASE("shader errors and bad context names are reported") {
    CHECK_THROWS_AS(gl::parse_context_kind("vulkan"), gl::GlError);
    auto context = context_or_skip();
    if (!context) return;
    const char* broken = "layout(local_size_x = 1) in;\nvoid main() { float x = bc_covers(); }\n";
    try {
        gl::Program program(context->gl(), {{GL_COMPUTE_SHADER, {glsl::kernel_source(), broken}}});
        FAIL("a broken shader compiled");
    } catch (const gl::GlError& e) {
        std::string message = e.what();
        CHECK(message.find("compilation failed") != std::string::npos);
        CHECK(message.find("covers") != std::string::npos);
    }
}

TEST_CASE("the embedded GLSL is the emitted library") {
    std::string_view text = glsl::kernel_source();
    CHECK(text.substr(0, 18) == "#version 450 core\n");
    CHECK(glsl::kernel_source_without_version().size() == text.size() - 18);
    for (const char* name : {"BC_FN bool covers(", "BC_FN ScreenBound screen_bound(", "BC_FN SampleBounds sample_bounds(",
                             "BC_FN PixelSample pixel_sample(", "#define real float"})
        CHECK_MESSAGE(text.find(name) != std::string_view::npos, name);
}
