// GPU/host parity of the raster glue (detail/raster_body.inl) and of the GL
// backend's shared buffer layouts (frontend/render/gl/gpu_layout_shared.h): a
// GLSL 4.50 compute shader built from the emitted blurcull_kernel.glsl runs
// every raster function on host-generated inputs in a headless Mesa context;
// the host runs kernel<float> on the same inputs. Every output must be
// bit-identical (0 differences) where the GL's arithmetic is IEEE-exact
// (probe_arithmetic: llvmpipe); on another GPU, or with BLURCULL_GL_TOLERANT=1,
// each output within what docs/glsl.md's model allows (compare_tolerant
// below). A second shader writes the shared structs, which the host reads
// through their C++ definitions.
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.

#include "gl_parity_helpers.hpp"

#include "render/gl/gpu_layout_shared.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;
using namespace blurcull::frontend::test;
using Kf = kernel<float>;

namespace {

constexpr int kInputs = 32768;
constexpr int kFloats = 58;   // per input, the layout of the shader's F() reads below
constexpr int kInts = 16;
constexpr int kOutputs = 31;  // uints (floats as their bits)

const char* const kNames[kOutputs] = {
    "raster_to_ndc.x", "raster_to_ndc.y", "ndc_to_raster.x", "ndc_to_raster.y", "pixel_sample_ndc.x",
    "pixel_sample_ndc.y", "pixel_rect_ndc.lo.x", "pixel_rect_ndc.lo.y", "pixel_rect_ndc.hi.x", "pixel_rect_ndc.hi.y",
    "box_cell_rect.x0", "box_cell_rect.y0", "box_cell_rect.x1", "box_cell_rect.y1", "interleaved_cell.x",
    "interleaved_cell.y", "interleaved_sample_ndc.x", "interleaved_sample_ndc.y", "sample_test bbox",
    "sample_test depth bbox", "sample_test hull", "sample_test depth hull", "sample_test dualspace",
    "sample_test depth dualspace", "sample_test two-stage", "sample_test depth two-stage", "depth_nearer",
    "depth_key", "depth_key_wins", "camera_coc.a", "camera_coc.b"};

const char* const kRasterMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Floats { float f_in[]; };
layout(std430, binding = 1) readonly buffer Ints { int i_in[]; };
layout(std430, binding = 2) writeonly buffer Results { uint result[]; };
uniform uint input_count;

void main() {
    uint id = gl_GlobalInvocationID.x;
    if (id >= input_count) return;
    int f = int(id) * 58, i = int(id) * 16, o = int(id) * 31;
    vec2 image_size = vec2(f_in[f], f_in[f + 1]);
    vec2 raster = vec2(f_in[f + 2], f_in[f + 3]);
    vec2 ndc = vec2(f_in[f + 4], f_in[f + 5]);
    vec2 offset = vec2(f_in[f + 6], f_in[f + 7]);
    vec2 lo = vec2(f_in[f + 8], f_in[f + 9]);
    vec2 hi = vec2(f_in[f + 10], f_in[f + 11]);
    vec2 cells = vec2(f_in[f + 12], f_in[f + 13]);
    vec2 jitter = vec2(f_in[f + 14], f_in[f + 15]);
    float near = f_in[f + 16];
    float depth_a = f_in[f + 17], depth_b = f_in[f + 18];
    vec3 lens = vec3(f_in[f + 19], f_in[f + 20], f_in[f + 21]);
    vec2 s = vec2(f_in[f + 22], f_in[f + 23]);
    vec2 uv = vec2(f_in[f + 24], f_in[f + 25]);
    float t = f_in[f + 26];
    MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = vec3(f_in[f + 27 + 3 * j], f_in[f + 28 + 3 * j], f_in[f + 29 + 3 * j]);
        tri.c[j] = vec2(f_in[f + 45 + 2 * j], f_in[f + 46 + 2 * j]);
    }
    float tri_near = f_in[f + 57];
    ivec2 pixel = ivec2(i_in[i], i_in[i + 1]);
    ivec4 rect = ivec4(i_in[i + 2], i_in[i + 3], i_in[i + 4], i_in[i + 5]);
    ivec2 cell = ivec2(i_in[i + 6], i_in[i + 7]);
    int scale = i_in[i + 8];
    ivec2 tile = ivec2(i_in[i + 9], i_in[i + 10]);
    int slot = i_in[i + 11], tile_width = i_in[i + 12];
    uint index_a = uint(i_in[i + 13]), index_b = uint(i_in[i + 14]);
    bool check_screen = i_in[i + 15] != 0;

    vec2 v = bc_raster_to_ndc(raster, image_size);
    result[o] = floatBitsToUint(v.x); result[o + 1] = floatBitsToUint(v.y);
    v = bc_ndc_to_raster(ndc, image_size);
    result[o + 2] = floatBitsToUint(v.x); result[o + 3] = floatBitsToUint(v.y);
    v = bc_pixel_sample_ndc(pixel, offset, image_size);
    result[o + 4] = floatBitsToUint(v.x); result[o + 5] = floatBitsToUint(v.y);
    vec4 box = bc_pixel_rect_ndc(rect, image_size);
    for (int k = 0; k < 4; ++k) result[o + 6 + k] = floatBitsToUint(box[k]);
    ivec4 r = bc_box_cell_rect(lo, hi, cells);
    for (int k = 0; k < 4; ++k) result[o + 10 + k] = uint(r[k]);
    ivec2 c = bc_interleaved_cell(tile, slot, tile_width);
    result[o + 14] = uint(c.x); result[o + 15] = uint(c.y);
    v = bc_interleaved_sample_ndc(cell, scale, jitter, image_size);
    result[o + 16] = floatBitsToUint(v.x); result[o + 17] = floatBitsToUint(v.y);
    for (int method = 0; method < 4; ++method) {
        ScreenBound sb = bc_screen_bound(tri, tri_near, method);
        SampleBounds b = bc_sample_bounds(tri, lo, hi, method);
        float depth;
        result[o + 18 + 2 * method] = uint(bc_sample_test(tri, sb, check_screen, b, s, uv, t, tri_near, depth));
        result[o + 19 + 2 * method] = floatBitsToUint(depth);
    }
    result[o + 26] = bc_depth_nearer(depth_a, depth_b) ? 1u : 0u;
    float key_a = bc_depth_key(near, depth_a), key_b = bc_depth_key(near, depth_b);
    result[o + 27] = floatBitsToUint(key_a);
    result[o + 28] = bc_depth_key_wins(key_a, index_a, key_b, index_b) ? 1u : 0u;
    v = bc_camera_coc(lens.x, lens.y, lens.z);
    result[o + 29] = floatBitsToUint(v.x); result[o + 30] = floatBitsToUint(v.y);
}
)glsl";

float edge_offset(Rng& rng) {
    int pick = rng.below(8);
    if (pick == 0) return 0.0f;
    if (pick == 1) return std::nextafter(1.0f, 0.0f);
    return std::min(static_cast<float>(rng.uniform(0.0, 1.0)), std::nextafter(1.0f, 0.0f));
}

struct Inputs {
    std::vector<float> floats;
    std::vector<std::int32_t> ints;
};

Inputs make_inputs(std::uint64_t seed) {
    Inputs in;
    Rng rng(seed);
    std::vector<Family> families = all_families();
    auto real = [&](double lo, double hi) { return static_cast<float>(rng.uniform(lo, hi)); };
    for (int n = 0; n < kInputs; ++n) {
        int w = 1 + rng.below(rng.below(2) ? 64 : 4096), h = 1 + rng.below(rng.below(2) ? 64 : 4096);
        int scale = 1 + rng.below(5);
        Config cfg = make_config(rng, families[static_cast<std::size_t>(n) % families.size()]);
        Kf::MovingTriangle tri = to_real<float>(cfg.tri);
        Sample5 sample = make_sample(rng, cfg);
        float lo_x = real(-1.2, 1.2), lo_y = real(-1.2, 1.2);
        // Boxes on a sample position now and then (the rect's edge cases).
        int px = rng.below(w), py = rng.below(h);
        float ox = edge_offset(rng), oy = edge_offset(rng);
        if (rng.below(4) == 0) {
            Kf::vec2 p = Kf::pixel_sample_ndc(Kf::ivec2(px, py), Kf::vec2(ox, oy), Kf::vec2(float(w), float(h)));
            lo_x = p.x;
            lo_y = p.y;
        }
        // Near the CPU footprint used for sample_bounds in the shader: the config's.
        bool sample_box = rng.below(2) == 0;
        float box_lo_x = sample_box ? static_cast<float>(cfg.s_lo.x) : lo_x;
        float box_lo_y = sample_box ? static_cast<float>(cfg.s_lo.y) : lo_y;
        float box_hi_x = sample_box ? static_cast<float>(cfg.s_hi.x) : lo_x + real(0.0, rng.below(2) ? 1e-3 : 1.0);
        float box_hi_y = sample_box ? static_cast<float>(cfg.s_hi.y) : lo_y + real(0.0, rng.below(2) ? 1e-3 : 1.0);
        float near = real(1e-3, 1.0);
        float depth_a = near * real(1.0, 1e4), depth_b = rng.below(8) == 0 ? depth_a : near * real(1.0, 1e4);
        float radius = rng.below(4) == 0 ? 0.0f : real(1e-4, 2.0);
        float focus = radius == 0.0f && rng.below(2) ? 0.0f : real(0.05, 100.0);
        float values[kFloats - 31] = {float(w), float(h), real(-10.0, w + 10.0), real(-10.0, h + 10.0), real(-1.5, 1.5),
                                      real(-1.5, 1.5), ox, oy, box_lo_x, box_lo_y, box_hi_x, box_hi_y,
                                      float(w * scale), float(h * scale), edge_offset(rng), edge_offset(rng), near,
                                      depth_a, depth_b, real(0.1, 20.0), radius, focus,
                                      static_cast<float>(sample.s.x), static_cast<float>(sample.s.y),
                                      static_cast<float>(sample.uv.x), static_cast<float>(sample.uv.y),
                                      static_cast<float>(sample.t)};
        in.floats.insert(in.floats.end(), values, values + (kFloats - 31));
        for (int j = 0; j < 6; ++j)
            for (int a = 0; a < 3; ++a) in.floats.push_back(tri.p[j][a]);
        for (int j = 0; j < 6; ++j)
            for (int a = 0; a < 2; ++a) in.floats.push_back(tri.c[j][a]);
        in.floats.push_back(static_cast<float>(cfg.near));
        int x1 = std::min(w - 1, px + rng.below(16)), y1 = std::min(h - 1, py + rng.below(16));
        int tile_width = 2 + rng.below(15);
        std::int32_t ints[kInts] = {px, py, px, py, x1, y1, rng.below(w * scale), rng.below(h * scale), scale,
                                    rng.below(700), rng.below(700), rng.below(tile_width * tile_width), tile_width,
                                    rng.below(100), rng.below(100), rng.below(4) != 0 ? 1 : 0};
        in.ints.insert(in.ints.end(), ints, ints + kInts);
    }
    return in;
}

std::vector<std::uint32_t> run_host(const Inputs& in) {
    std::vector<std::uint32_t> out(static_cast<std::size_t>(kInputs) * kOutputs);
    for (int n = 0; n < kInputs; ++n) {
        const float* f = &in.floats[static_cast<std::size_t>(n) * kFloats];
        const std::int32_t* i = &in.ints[static_cast<std::size_t>(n) * kInts];
        std::uint32_t* o = &out[static_cast<std::size_t>(n) * kOutputs];
        Kf::vec2 image_size(f[0], f[1]), lo(f[8], f[9]), hi(f[10], f[11]), cells(f[12], f[13]), jitter(f[14], f[15]);
        Kf::vec2 v = Kf::raster_to_ndc(Kf::vec2(f[2], f[3]), image_size);
        o[0] = bits_of(v.x), o[1] = bits_of(v.y);
        v = Kf::ndc_to_raster(Kf::vec2(f[4], f[5]), image_size);
        o[2] = bits_of(v.x), o[3] = bits_of(v.y);
        v = Kf::pixel_sample_ndc(Kf::ivec2(i[0], i[1]), Kf::vec2(f[6], f[7]), image_size);
        o[4] = bits_of(v.x), o[5] = bits_of(v.y);
        Kf::vec4 box = Kf::pixel_rect_ndc(Kf::ivec4(i[2], i[3], i[4], i[5]), image_size);
        for (int k = 0; k < 4; ++k) o[6 + k] = bits_of(box[k]);
        Kf::ivec4 r = Kf::box_cell_rect(lo, hi, cells);
        for (int k = 0; k < 4; ++k) o[10 + k] = static_cast<std::uint32_t>(r[k]);
        Kf::ivec2 c = Kf::interleaved_cell(Kf::ivec2(i[9], i[10]), i[11], i[12]);
        o[14] = static_cast<std::uint32_t>(c.x), o[15] = static_cast<std::uint32_t>(c.y);
        v = Kf::interleaved_sample_ndc(Kf::ivec2(i[6], i[7]), i[8], jitter, image_size);
        o[16] = bits_of(v.x), o[17] = bits_of(v.y);
        Kf::MovingTriangle tri;
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = Kf::vec3(f[27 + 3 * j], f[28 + 3 * j], f[29 + 3 * j]);
            tri.c[j] = Kf::vec2(f[45 + 2 * j], f[46 + 2 * j]);
        }
        for (int method = 0; method < 4; ++method) {
            Kf::ScreenBound sb = Kf::screen_bound(tri, f[57], method);
            Kf::SampleBounds b = Kf::sample_bounds(tri, lo, hi, method);
            float depth = 0.0f;
            o[18 + 2 * method] = static_cast<std::uint32_t>(
                Kf::sample_test(tri, sb, i[15] != 0, b, Kf::vec2(f[22], f[23]), Kf::vec2(f[24], f[25]), f[26], f[57], depth));
            o[19 + 2 * method] = bits_of(depth);
        }
        o[26] = Kf::depth_nearer(f[17], f[18]) ? 1u : 0u;
        float key_a = Kf::depth_key(f[16], f[17]), key_b = Kf::depth_key(f[16], f[18]);
        o[27] = bits_of(key_a);
        o[28] = Kf::depth_key_wins(key_a, static_cast<std::uint32_t>(i[13]), key_b, static_cast<std::uint32_t>(i[14])) ? 1u : 0u;
        v = Kf::camera_coc(f[19], f[20], f[21]);
        o[29] = bits_of(v.x), o[30] = bits_of(v.y);
    }
    return out;
}

std::vector<std::uint32_t> run_gpu(const gl::HeadlessContext& context, const Inputs& in) {
    const gl::Functions& f = context.gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), kRasterMain}}});
    auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
    gl::Buffer floats(f, GL_SHADER_STORAGE_BUFFER, bytes(in.floats), in.floats.data());
    gl::Buffer ints(f, GL_SHADER_STORAGE_BUFFER, bytes(in.ints), in.ints.data());
    std::vector<std::uint32_t> out(static_cast<std::size_t>(kInputs) * kOutputs, 0xdeadbeefu);
    gl::Buffer results(f, GL_SHADER_STORAGE_BUFFER, bytes(out), out.data());
    floats.bind_base(0);
    ints.bind_base(1);
    results.bind_base(2);
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "input_count"), static_cast<std::uint32_t>(kInputs));
    f.DispatchCompute((kInputs + 63) / 64, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    gl::check_gl(f, "running the raster parity shader");
    results.read(out.data(), bytes(out));
    f.UseProgram(0);
    return out;
}

std::string read_text(const std::string& path) {
    std::ifstream file(path);
    REQUIRE_MESSAGE(file.good(), "cannot read " << path);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// Writes one of each shared struct with recognisable values: member m of
// struct s, component k, holds 1000 s + 10 m + k (as int or float).
const char* const kLayoutMain = R"glsl(
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = 1) writeonly buffer Cells { CellBounds cells[]; };
layout(std430, binding = 2) writeonly buffer Boxes { MethodBox boxes[]; };
layout(std430, binding = 3) writeonly buffer Triangles { MovingTriangle triangles[]; };
vec4 fv(int s, int m) { return vec4(1000 * s + 10 * m) + vec4(0, 1, 2, 3); }
ivec4 iv(int s, int m) { return ivec4(1000 * s + 10 * m) + ivec4(0, 1, 2, 3); }
void main() {
    for (int e = 0; e < 2; ++e) {  // two elements: the array stride too
        int s = 1 + 10 * e;
        TriangleInfo info;
        info.box = fv(s, 0); info.rect = iv(s, 1);
        ivec4 counts = iv(s, 2);
        info.needs = counts.x; info.hull_count = counts.y; info.path = counts.z; info.padding = counts.w;
        info.outline01 = fv(s, 3); info.outline2 = fv(s, 4);
        for (int k = 0; k < BC_HULL_MAX; ++k) info.hull[k] = fv(s, 5 + k);
        infos[e] = info;
        CellBounds cell;
        cell.rect = iv(s + 1, 0); cell.lens = fv(s + 1, 1); cell.time_lines_u_a = fv(s + 1, 2);
        cell.time_lines_u_b = fv(s + 1, 3); cell.time_lines_v_a = fv(s + 1, 4); cell.time_lines_v_b = fv(s + 1, 5);
        cells[e] = cell;
        MethodBox box;
        box.quad = iv(s + 2, 0); box.rect = iv(s + 2, 1); box.box = fv(s + 2, 2); box.index = iv(s + 2, 3);
        boxes[e] = box;
        MovingTriangle tri;
        for (int j = 0; j < 6; ++j) { tri.p[j] = fv(s + 3, j).xyz; tri.c[j] = fv(s + 3, 6 + j).xy; }
        triangles[e] = tri;
    }
}
)glsl";

template <class V>
bool holds(V v, int s, int m) {
    for (int k = 0; k < V::length(); ++k)
        if (v[k] != static_cast<typename V::value_type>(1000 * s + 10 * m + k)) return false;
    return true;
}

// What a GPU may differ in (docs/glsl.md, "Parity on a GPU"):
// - NDC and raster positions (one division, sums of at most a few
//   magnitudes): within kDivisionUlps ULPs of 2 (NDC) or of the image size
//   (raster), or of the value when larger;
// - box_cell_rect's cells: one cell at most (a floor of a position within
//   rounding of a cell's edge);
// - interleaved_cell, depth_nearer: integer arithmetic and comparisons, identical;
// - sample_test: a different verdict only where covers' is near an edge
//   (covers_condition within kEdgeTolerance) or where neither verdict is a
//   hit (culled and missed both mean no hit); the depth of a hit on both
//   within kEdgeTolerance times its condition plus kDivisionUlps;
// - depth_key (one division): kDivisionUlps; depth_key_wins only where the
//   host's two keys are within 2 kDivisionUlps of each other;
// - camera_coc: a exact, b (one division) within kDivisionUlps.
struct RasterTolerance {
    ToleranceTally values;
    std::vector<long> within_by_output = std::vector<long>(kOutputs, 0);
};

RasterTolerance compare_tolerant(const Inputs& in, const std::vector<std::uint32_t>& host,
                                 const std::vector<std::uint32_t>& gpu) {
    RasterTolerance tol;
    for (std::size_t n = 0; n < static_cast<std::size_t>(kInputs); ++n) {
        const float* f = &in.floats[n * kFloats];
        const std::uint32_t* h = &host[n * kOutputs];
        const std::uint32_t* g = &gpu[n * kOutputs];
        const double size = std::max(f[0], f[1]);
        for (int k = 0; k < kOutputs; ++k) {
            if (h[k] == g[k]) continue;
            const float hv = float_of(h[k]), gv = float_of(g[k]);
            bool allowed = false;
            if (k <= 9 || k == 16 || k == 17) {
                allowed = within_ulps_of(hv, gv, k == 2 || k == 3 ? size : 2.0, kDivisionUlps);
            } else if (k <= 13) {
                const auto d = static_cast<std::int64_t>(static_cast<std::int32_t>(h[k])) -
                               static_cast<std::int64_t>(static_cast<std::int32_t>(g[k]));
                allowed = d >= -1 && d <= 1;
            } else if (k >= 18 && k <= 25) {
                const int method_at = 18 + 2 * ((k - 18) / 2);
                Kf::MovingTriangle tri;
                for (int j = 0; j < 6; ++j) {
                    tri.p[j] = Kf::vec3(f[27 + 3 * j], f[28 + 3 * j], f[29 + 3 * j]);
                    tri.c[j] = Kf::vec2(f[45 + 2 * j], f[46 + 2 * j]);
                }
                const CoversCondition cond =
                    covers_condition(tri, Kf::vec2(f[22], f[23]), Kf::vec2(f[24], f[25]), f[26], f[57]);
                const bool host_hit = h[method_at] == BC_SAMPLE_COVERED, gpu_hit = g[method_at] == BC_SAMPLE_COVERED;
                if (k == method_at) {
                    allowed = (!host_hit && !gpu_hit) || cond.margin <= kEdgeTolerance;
                } else if (host_hit && gpu_hit) {
                    const double hd = hv;
                    allowed = std::abs(hd - double(gv)) <= kEdgeTolerance * cond.depth_condition * std::abs(hd) +
                                                               kDivisionUlps * std::ldexp(1.0, std::ilogb(std::max(std::abs(hd), 0x1p-126)) - 23);
                } else {
                    allowed = !host_hit || !gpu_hit;  // a depth without a hit on one side: its verdict is judged
                }
            } else if (k == 27 || k == 30) {
                allowed = within_ulps_of(hv, gv, 0.0, kDivisionUlps);
            } else if (k == 28) {
                allowed = ulp_distance(Kf::depth_key(f[16], f[17]), Kf::depth_key(f[16], f[18])) <= 2 * kDivisionUlps;
            }
            if (allowed) ++tol.within_by_output[static_cast<std::size_t>(k)];
            char text[200];
            std::snprintf(text, sizeof text, "%s of input %zu: host 0x%08x (%.9g), GPU 0x%08x (%.9g)", kNames[k], n,
                          h[k], double(hv), g[k], double(gv));
            tol.values.note(allowed, text);
        }
    }
    return tol;
}

}  // namespace

TEST_CASE("the raster glue in GLSL computes what the host kernel<float> computes, bit for bit") {
    auto context = context_or_skip();
    if (!context) return;
    Inputs in = make_inputs(0x7a57e2ull);
    std::vector<std::uint32_t> gpu = run_gpu(*context, in);
    std::vector<std::uint32_t> host = run_host(in);
    long differing = 0;
    std::vector<long> by_output(kOutputs, 0);
    long covered = 0, rect_nonempty = 0;
    for (std::size_t n = 0; n < static_cast<std::size_t>(kInputs); ++n) {
        for (int k = 0; k < kOutputs; ++k) {
            std::size_t at = n * kOutputs + static_cast<std::size_t>(k);
            if (host[at] != gpu[at]) {
                if (differing == 0) MESSAGE("first difference: " << kNames[k] << " of input " << n << ": host 0x" << std::hex << host[at] << ", GPU 0x" << gpu[at]);
                ++differing;
                ++by_output[static_cast<std::size_t>(k)];
            }
        }
        for (int method = 0; method < 4; ++method) covered += host[n * kOutputs + 18 + 2 * static_cast<std::size_t>(method)] == BC_SAMPLE_COVERED;
        rect_nonempty += static_cast<std::int32_t>(host[n * kOutputs + 10]) <= static_cast<std::int32_t>(host[n * kOutputs + 12]);
    }
    for (int k = 0; k < kOutputs; ++k)
        if (by_output[static_cast<std::size_t>(k)] > 0) MESSAGE("  " << kNames[k] << ": " << by_output[static_cast<std::size_t>(k)] << " differ");
    MESSAGE(context->renderer() << ": " << kInputs << " inputs x " << kOutputs << " outputs, " << differing
                                << " differ; " << covered << " covered samples, " << rect_nonempty << " non-empty rects");
    const ArithmeticProbe probe = probe_arithmetic(*context);
    MESSAGE(probe.describe());
    if (!probe.tolerant()) {
        CHECK(differing == 0);
    } else {
        const RasterTolerance tol = compare_tolerant(in, host, gpu);
        MESSAGE("tolerant comparison (edge tolerance " << kEdgeTolerance << ", " << kDivisionUlps << " ULP through a division, "
                << "cells +-1): " << tol.values.within << " differ within the model's limits, " << tol.values.outside
                << " outside");
        for (int k = 0; k < kOutputs; ++k)
            if (tol.within_by_output[static_cast<std::size_t>(k)] > 0)
                MESSAGE("  " << kNames[k] << ": " << tol.within_by_output[static_cast<std::size_t>(k)] << " within");
        CHECK_MESSAGE(tol.values.outside == 0, tol.values.first_outside);
        if (probe.exact) CHECK(differing == 0);
    }
    // The comparison saw real work.
    CHECK(covered > 1000);
    CHECK(rect_nonempty > kInputs / 4);
}

TEST_CASE("gpu_layout_shared.h: the GLSL structs have the C++ structs' std430 layout") {
    auto context = context_or_skip();
    if (!context) return;
    using namespace blurcull::frontend::gpu;
    const std::string layout = read_text(std::string(BLURCULL_SOURCE_DIR) + "/frontend/render/gl/gpu_layout_shared.h");
    const gl::Functions& f = context->gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), layout, kLayoutMain}}});
    std::vector<TriangleInfo> infos(2);
    std::vector<CellBounds> cells(2);
    std::vector<MethodBox> boxes(2);
    std::vector<GpuMovingTriangle> triangles(2);
    gl::Buffer info_buffer(f, GL_SHADER_STORAGE_BUFFER, 2 * sizeof(TriangleInfo));
    gl::Buffer cell_buffer(f, GL_SHADER_STORAGE_BUFFER, 2 * sizeof(CellBounds));
    gl::Buffer box_buffer(f, GL_SHADER_STORAGE_BUFFER, 2 * sizeof(MethodBox));
    gl::Buffer triangle_buffer(f, GL_SHADER_STORAGE_BUFFER, 2 * sizeof(GpuMovingTriangle));
    info_buffer.bind_base(0);
    cell_buffer.bind_base(1);
    box_buffer.bind_base(2);
    triangle_buffer.bind_base(3);
    f.UseProgram(program.id());
    f.DispatchCompute(1, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    gl::check_gl(f, "running the layout shader");
    info_buffer.read(infos.data(), 2 * sizeof(TriangleInfo));
    cell_buffer.read(cells.data(), 2 * sizeof(CellBounds));
    box_buffer.read(boxes.data(), 2 * sizeof(MethodBox));
    triangle_buffer.read(triangles.data(), 2 * sizeof(GpuMovingTriangle));
    f.UseProgram(0);
    for (int e = 0; e < 2; ++e) {
        CAPTURE(e);
        int s = 1 + 10 * e;
        const TriangleInfo& info = infos[static_cast<std::size_t>(e)];
        CHECK(holds(info.box, s, 0));
        CHECK(holds(info.rect, s, 1));
        CHECK(holds(glm::ivec4(info.needs, info.hull_count, info.path, info.padding), s, 2));
        CHECK(holds(info.outline01, s, 3));
        CHECK(holds(info.outline2, s, 4));
        for (int k = 0; k < BC_HULL_MAX; ++k) CHECK(holds(info.hull[k], s, 5 + k));
        const CellBounds& cell = cells[static_cast<std::size_t>(e)];
        CHECK(holds(cell.rect, s + 1, 0));
        CHECK(holds(cell.lens, s + 1, 1));
        CHECK(holds(cell.time_lines_u_a, s + 1, 2));
        CHECK(holds(cell.time_lines_u_b, s + 1, 3));
        CHECK(holds(cell.time_lines_v_a, s + 1, 4));
        CHECK(holds(cell.time_lines_v_b, s + 1, 5));
        const MethodBox& box = boxes[static_cast<std::size_t>(e)];
        CHECK(holds(box.quad, s + 2, 0));
        CHECK(holds(box.rect, s + 2, 1));
        CHECK(holds(box.box, s + 2, 2));
        CHECK(holds(box.index, s + 2, 3));
        const GpuMovingTriangle& tri = triangles[static_cast<std::size_t>(e)];
        for (int j = 0; j < 6; ++j) {
            CHECK(holds(glm::vec3(tri.p[j]), s + 3, j));
            CHECK(holds(tri.c[j], s + 3, 6 + j));
        }
    }
    // to_gpu puts the kernel's float triangle where the shaders read it.
    Kf::MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = Kf::vec3(float(j), float(j) + 0.5f, float(j) + 0.25f);
        tri.c[j] = Kf::vec2(float(-j), float(j) * 2.0f);
    }
    GpuMovingTriangle gpu = to_gpu(tri);
    for (int j = 0; j < 6; ++j) {
        CHECK(glm::vec3(gpu.p[j]) == tri.p[j]);
        CHECK(gpu.p[j].w == 0.0f);
        CHECK(gpu.c[j] == tri.c[j]);
    }
}

// The tolerant comparison's own check, no GL needed: the host's outputs as a
// "GPU" with injected differences the model allows and forbids.
TEST_CASE("the raster tolerant comparison accepts what the model allows and flags what it forbids") {
    const Inputs in = make_inputs(0x7a57e3ull);
    const std::vector<std::uint32_t> host = run_host(in);
    CHECK(compare_tolerant(in, host, host).values.within == 0);
    std::vector<std::uint32_t> gpu = host;
    gpu[0 * kOutputs + 30] = bits_of(std::nextafter(float_of(host[30]), 1e30f));  // camera_coc.b: 1 ULP
    gpu[1 * kOutputs + 14] = host[kOutputs + 14] + 1u;                            // interleaved_cell.x: exact
    gpu[2 * kOutputs + 10] = host[2 * kOutputs + 10] + 1u;                        // box_cell_rect.x0: one cell
    gpu[3 * kOutputs + 0] = bits_of(float_of(host[3 * kOutputs]) + 0.01f);       // raster_to_ndc.x: far off
    const RasterTolerance tol = compare_tolerant(in, host, gpu);
    CHECK(tol.values.within == 2);
    CHECK(tol.values.outside == 2);
}
