// The GL backend's compute pipeline (frontend/render/gl/gl_compute_pipeline.hpp,
// GlOptions::pipeline = compute): the same samples decided the same way as
// the cpu backend's float path and the fragment pipeline (hits, sample ids,
// pixels) on the built-in scenes and the Khronos sample models (on a GPU
// that does not compute as the host, within issue 22's arithmetic model),
// every cull method, a forced tile-list overflow, triangle batches (any size
// gives the same ids; a scene past one dispatch), and the command line
// (--gl-pipeline, the JSON, progress). No GL context: SKIPPED, or a failure
// when CI=true. One CTest per case (tests/CMakeLists.txt).
#include "gl_render_reference.hpp"  // first: it keeps the host from contracting a*b+c
#include "cli_runner.hpp"
#include "frontend_test_helpers.hpp"
#include "render/common/cull_method.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "test_data_dirs.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

RenderSettings settings_for(int width, int height, int spp) {
    RenderSettings settings = quiet_settings(width, height, spp);
    settings.seed = 3;
    return settings;
}

// Occlusion off: samples_hit then counts every covered sample, as the
// fragment pipeline's and the cpu's with occlusion off do.
GlOptions compute_options(bool occlusion = false) {
    GlOptions options;
    options.pipeline = GlPipeline::compute;
    options.keep_sample_ids = true;
    options.occlusion = occlusion;
    return options;
}

double counter(const RenderStats& stats, const std::string& name) {
    for (const auto& [key, value] : stats.counters)
        if (key == name) return value;
    FAIL("no counter " << name);
    return -1.0;
}

// The compute pipeline's sample ids and hits against the cpu float path's
// (`cpu_ids`, `cpu`: render_cpu in float, occlusion off). Where the GL
// computes as the host (llvmpipe), the very same ids, hits and image;
// elsewhere every differing sample explained by the GPU arithmetic model
// against the host's float decisions (reference_samples<float>,
// compare_sample_ids, docs/glsl.md: near an edge, or a depth tie within a
// division's rounding), the hits within the pairs near an edge of the cpu's,
// the image within what those samples can move it (per-hit shading apart:
// then within 0.01).
void check_float_decisions(GlRenderer& gl, const Scene& scene, const RenderSettings& settings,
                           const RenderResult& compute, const std::vector<std::uint32_t>& ids,
                           const RenderResult& cpu, const std::vector<std::uint32_t>& cpu_ids) {
    const auto compute_hits = static_cast<double>(compute.stats.samples_hit);
    const auto cpu_hits = static_cast<double>(cpu.stats.samples_hit);
    INFO("hits compute ", compute_hits, " cpu float ", cpu_hits, ", rmse ", rmse(compute.image, cpu.image));
    CHECK(compute_hits > 0.0);
    if (!render_probe(gl).tolerant()) {
        // The same ids but where two triangles' distinct float depths round
        // to one depth key near / w (raster_body.inl: the cpu keeps the
        // nearer, the GPU rule the lower index).
        REQUIRE(ids.size() == cpu_ids.size());
        long differ = 0, key_ties = 0;
        if (ids != cpu_ids) {
            using K = blurcull::kernel<float>;
            const SampleReference<float> ref = reference_samples<float>(scene, settings);
            for (std::size_t k = 0; k < ids.size(); ++k) {
                if (ids[k] == cpu_ids[k]) continue;
                ++differ;
                if (ids[k] == no_triangle || cpu_ids[k] == no_triangle) continue;
                const auto& sample = ref.samples[k];
                float za = 0.0f, zb = 0.0f;
                if (K::covers(ref.triangles[cpu_ids[k]], sample.ndc, sample.lens, sample.time, ref.near, za) &&
                    K::covers(ref.triangles[ids[k]], sample.ndc, sample.lens, sample.time, ref.near, zb) &&
                    K::depth_key(ref.near, za) == K::depth_key(ref.near, zb)) {
                    ++key_ties;
                }
            }
        }
        INFO(differ, " samples show another triangle than the cpu's, ", key_ties, " of them depth-key ties");
        CHECK(differ == key_ties);
        CHECK(compute_hits == cpu_hits);
        CHECK(same_pixels(compute.image, cpu.image));
        return;
    }
    const SampleReference<float> ref = reference_samples<float>(scene, settings, true);
    const SampleIdComparison cmp = compare_sample_ids(scene, ref, ids, settings.spp);
    INFO(cmp.near_edge, " near an edge, ", cmp.depth_tie, " depth ties; first outside the model: ",
         cmp.first_outside);
    CHECK(cmp.outside == 0);
    CHECK(std::abs(compute_hits - cpu_hits) <= double(ref.pairs_near_edge));
    CHECK(rmse(compute.image, cpu.image) <= std::max(cmp.image_rmse_limit + 1e-6, 0.01));
}

bool has_phase(const RenderStats& stats, const std::string& name) {
    for (const auto& entry : stats.ms_per_phase)
        if (entry.first == name) return entry.second >= 0.0;
    return false;
}

}  // namespace

TEST_CASE("gl compute pipeline: every built-in scene gives the cpu float path's hits and pixels") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // 128x96, 4 spp, against the cpu float path: the same arithmetic
    // (kernel<float> and its GLSL twin are bit-identical on llvmpipe).
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = small_scene(name, 128, 96);
        const RenderSettings settings = settings_for(128, 96, 4);
        CpuOptions cpu_options;
        cpu_options.occlusion = false;  // samples_hit counts every covered sample, as GL's does
        cpu_options.precision = KernelPrecision::float32;
        std::vector<std::uint32_t> cpu_ids, ids;
        const RenderResult cpu = render_cpu(scene, settings, cpu_options, &cpu_ids);
        const RenderResult compute = gl->render(scene, settings, compute_options(), &ids);
        std::printf("%-10s 128x96 4 spp: hits compute %llu cpu float %llu, rmse %.6f, tested %llu, %.0f ms\n",
                    name.c_str(), static_cast<unsigned long long>(compute.stats.samples_hit),
                    static_cast<unsigned long long>(cpu.stats.samples_hit), rmse(compute.image, cpu.image),
                    static_cast<unsigned long long>(compute.stats.samples_tested), compute.stats.ms_total);
        INFO(name);
        check_float_decisions(*gl, scene, settings, compute, ids, cpu, cpu_ids);
        CHECK(compute.stats.samples_tested >= compute.stats.samples_hit);
        CHECK(compute.stats.triangles == scene.triangles.size());
        CHECK(counter(compute.stats, "tile_list_retries") == 0.0);
        for (const char* phase : {"gpu_setup", "gpu_binning", "gpu_raster", "gpu_resolve", "wall_raster"}) {
            CHECK(has_phase(compute.stats, phase));
        }
    }
}

// The Khronos sample models of tests/data/khronos (files nobody here wrote:
// animated, skinned, morphed, textured, with cameras), each with a moving
// shutter and a lens, under every cull method: the host's float decisions
// sample by sample, and the cpu float path's image.
TEST_CASE("gl compute pipeline: the Khronos sample models, every cull, as the cpu float path") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const std::string dir = blurcull::testing::khronos_test_dir();
    int models = 0;
    for (const std::string file : {"AnimatedTriangle.gltf", "BoxAnimated.gltf", "Cameras.gltf", "Cube/Cube.gltf",
                                   "RiggedFigure.gltf", "RiggedSimple.gltf",
                                   "SparseMorphCube/singleBlendshapeCube_sparse.glb"}) {
        GltfOptions options;
        options.aspect = 96.0f / 72.0f;
        options.motion_segments = 1;      // the gl backend's one linear motion
        options.shutter_close = 0.25f;    // a quarter second: visible motion in the animated ones
        options.lens_radius = 0.02f;      // and a little defocus (focus: the scene's centre)
        const Scene scene = load_gltf_scene(dir + "/" + file, options, [](const std::string&) {});
        ++models;
        RenderSettings settings = settings_for(96, 72, 8);  // two chunks of samples
        CpuOptions cpu_options;
        cpu_options.occlusion = false;
        cpu_options.precision = KernelPrecision::float32;
        std::vector<std::uint32_t> cpu_ids;
        const RenderResult cpu = render_cpu(scene, settings, cpu_options, &cpu_ids);
        for (const CullMethodInfo& method : cull_methods()) {
            settings.cull = method.method;
            std::vector<std::uint32_t> ids;
            const RenderResult compute = gl->render(scene, settings, compute_options(), &ids);
            INFO(file, " (", scene.triangles.size(), " triangles), cull ", std::string(method.name));
            check_float_decisions(*gl, scene, settings, compute, ids, cpu, cpu_ids);
        }
    }
    CHECK(models == 7);
}

TEST_CASE("gl compute pipeline: the fragment pipeline's samples") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // The hand (defocus) and the car (motion, static parts): the fragment
    // pipeline's cost on llvmpipe is per primitive, the forest takes minutes.
    for (const std::string name : {"hand", "car"}) {
        const Scene scene = small_scene(name, 96, 72);
        const RenderSettings settings = settings_for(96, 72, 4);
        std::vector<std::uint32_t> ids, fragment_ids;
        const RenderResult compute = gl->render(scene, settings, compute_options(), &ids);
        GlOptions fragment_options;
        fragment_options.keep_sample_ids = true;
        const RenderResult fragment = gl->render(scene, settings, fragment_options, &fragment_ids);
        INFO(name);
        CHECK(compute.stats.samples_hit == fragment.stats.samples_hit);
        // The fragment pipeline gives a depth tie between a static and a
        // moving triangle to the static one (drawn first); the compute
        // pipeline, as the cpu, to the lower index.
        CHECK(fraction_equal(ids, fragment_ids) >= 0.9999);
        CHECK(rmse(compute.image, fragment.image) < 0.001);
    }
}

TEST_CASE("gl compute pipeline: every cull method and sampler, the same decisions") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const Scene scene = small_scene("car", 64, 48);
    RenderSettings settings = settings_for(64, 48, 8);
    std::vector<std::uint32_t> reference_ids;
    const RenderResult reference = gl->render(scene, settings, compute_options(), &reference_ids);
    for (const CullMethodInfo& method : cull_methods()) {
        settings.cull = method.method;
        std::vector<std::uint32_t> ids;
        const RenderResult result = gl->render(scene, settings, compute_options(), &ids);
        INFO(method.name, ": tested ", result.stats.samples_tested, " of ", reference.stats.samples_tested);
        CHECK(ids == reference_ids);
        CHECK(result.stats.samples_hit == reference.stats.samples_hit);
        CHECK(same_pixels(result.image, reference.image));
        if (method.bounds_samples) CHECK(result.stats.samples_tested <= reference.stats.samples_tested);
    }
    // Every sampler draws the cpu's samples (cpu float path, same image).
    settings.cull = CullMethod::two_stage;
    CpuOptions cpu_options;
    cpu_options.occlusion = false;
    cpu_options.precision = KernelPrecision::float32;
    for (int sampler : {BC_PATTERN_HASHED, BC_PATTERN_RANDOM}) {
        settings.sampler = sampler;
        const RenderResult cpu = render_cpu(scene, settings, cpu_options);
        const RenderResult compute = gl->render(scene, settings, compute_options());
        INFO("sampler ", sampler);
        CHECK(compute.stats.samples_hit == cpu.stats.samples_hit);
        CHECK(same_pixels(compute.image, cpu.image));
    }
}

TEST_CASE("gl compute pipeline: shutter slices' screen boxes skip samples, never a hit") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // Motion (car, dragonfly: bbox, twostage) and defocus only (hand).
    for (const std::string name : {"car", "dragonfly", "hand"}) {
        const Scene scene = small_scene(name, 96, 72);
        RenderSettings settings = settings_for(96, 72, 4);
        settings.cull = name == "dragonfly" ? CullMethod::two_stage : CullMethod::bbox;
        GlOptions whole = compute_options();
        whole.time_strata = false;
        std::vector<std::uint32_t> ids, sliced_ids;
        const RenderResult all = gl->render(scene, settings, whole, &ids);
        const RenderResult sliced = gl->render(scene, settings, compute_options(), &sliced_ids);
        std::printf("%-9s 96x72 4 spp %s: tested %llu -> %llu with shutter slices, hits %llu\n", name.c_str(),
                    to_string(settings.cull), static_cast<unsigned long long>(all.stats.samples_tested),
                    static_cast<unsigned long long>(sliced.stats.samples_tested),
                    static_cast<unsigned long long>(sliced.stats.samples_hit));
        INFO(name);
        CHECK(sliced_ids == ids);
        CHECK(sliced.stats.samples_hit == all.stats.samples_hit);
        CHECK(same_pixels(sliced.image, all.image));
        // The hand only defocuses: slices of the shutter do not narrow it.
        if (name == "hand") {
            CHECK(sliced.stats.samples_tested == all.stats.samples_tested);
        } else {
            CHECK(sliced.stats.samples_tested * 2 < all.stats.samples_tested);
        }
    }
}

TEST_CASE("gl compute pipeline: occlusion per tile skips work, never a winner") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // The forest (deep, many layers) and the car, at 96x72, 8 spp: two
    // chunks of samples, so the held keys carry over between dispatches.
    for (const std::string name : {"forest", "car"}) {
        const Scene scene = small_scene(name, 96, 72);
        const RenderSettings settings = settings_for(96, 72, 8);
        std::vector<std::uint32_t> ids, occluded_ids;
        const RenderResult all = gl->render(scene, settings, compute_options(false), &ids);
        const RenderResult occluded = gl->render(scene, settings, compute_options(true), &occluded_ids);
        std::printf("%-6s 96x72 8 spp: tested %llu -> %llu, hits %llu -> %llu, entries occluded %.0f\n", name.c_str(),
                    static_cast<unsigned long long>(all.stats.samples_tested),
                    static_cast<unsigned long long>(occluded.stats.samples_tested),
                    static_cast<unsigned long long>(all.stats.samples_hit),
                    static_cast<unsigned long long>(occluded.stats.samples_hit),
                    counter(occluded.stats, "occluded_entries"));
        INFO(name);
        CHECK(occluded_ids == ids);
        CHECK(same_pixels(occluded.image, all.image));
        CHECK(counter(all.stats, "occluded_entries") == 0.0);
        CHECK(counter(occluded.stats, "occluded_entries") > 0.0);
        CHECK(occluded.stats.samples_tested < all.stats.samples_tested);
        CHECK(occluded.stats.samples_hit < all.stats.samples_hit);
    }
}

TEST_CASE("gl compute pipeline: alpha masks and per-hit shading as the cpu float path") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // tests/data/shading: COLOR_0 and texture alpha masks (MASK), vertex
    // colours and textures resolved per hit on the host from the ids.
    const std::string data = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/shading/";
    for (const char* file : {"attributes.gltf", "mask_texture.gltf"}) {
        Scene scene = load_gltf_scene(data + file, GltfOptions{}, [](const std::string&) {});
        for (int variant = 0; variant < 2; ++variant) {
            if (variant == 1) {  // defocus: the lens and time bounds and the hull
                scene.camera.lens_radius = 0.08f;
                scene.camera.focus_distance = 4.0f;
            }
            RenderSettings settings = settings_for(96, 72, 8);
            settings.cull = variant == 1 ? CullMethod::two_stage : CullMethod::bbox;
            CpuOptions cpu_options;
            cpu_options.occlusion = false;
            cpu_options.precision = KernelPrecision::float32;
            const RenderResult cpu = render_cpu(scene, settings, cpu_options);
            const RenderResult compute = gl->render(scene, settings, compute_options());
            INFO(file, ", variant ", variant, ": hits compute ", compute.stats.samples_hit, " cpu ",
                 cpu.stats.samples_hit, ", rmse ", rmse(compute.image, cpu.image));
            CHECK(compute.stats.samples_hit == cpu.stats.samples_hit);
            CHECK(same_pixels(compute.image, cpu.image));
        }
    }
}

TEST_CASE("gl compute pipeline: an overflowing tile list is binned again, the same image") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const Scene scene = small_scene("dragonfly", 96, 72);
    const RenderSettings settings = settings_for(96, 72, 4);
    std::vector<std::uint32_t> ids, tiny_ids;
    const RenderResult normal = gl->render(scene, settings, compute_options(), &ids);
    GlOptions tiny = compute_options();
    tiny.tile_list_capacity = 1;  // far below what the lists need
    const RenderResult forced = gl->render(scene, settings, tiny, &tiny_ids);
    CHECK(counter(normal.stats, "tile_list_retries") == 0.0);
    CHECK(counter(forced.stats, "tile_list_retries") == 1.0);
    CHECK(counter(forced.stats, "tile_list_entries") == counter(normal.stats, "tile_list_entries"));
    CHECK(counter(forced.stats, "tile_list_capacity") == counter(forced.stats, "tile_list_entries"));
    CHECK(counter(normal.stats, "tile_list_entries") > 1000.0);
    CHECK(tiny_ids == ids);
    CHECK(forced.stats.samples_hit == normal.stats.samples_hit);
    CHECK(forced.stats.samples_tested == normal.stats.samples_tested);
    CHECK(same_pixels(forced.image, normal.image));
}

TEST_CASE("gl compute pipeline: triangles in batches, the same samples whatever the batch") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    // The forest with occlusion (the held depth keys carry between batches)
    // and a texture-masked model with one material made BLEND (the mask and
    // the blend hash take the scene index, the kernel the batch's).
    const std::string data = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/shading/";
    Scene masked = load_gltf_scene(data + "mask_texture.gltf", GltfOptions{}, [](const std::string&) {});
    REQUIRE(masked.materials.size() >= 1);
    masked.materials.back().alpha_mode = AlphaMode::blend;
    masked.camera.lens_radius = 0.05f;
    masked.camera.focus_distance = 4.0f;
    const Scene forest = small_scene("forest", 96, 72);
    for (const Scene* scene : {&forest, static_cast<const Scene*>(&masked)}) {
        const RenderSettings settings = settings_for(96, 72, 8);
        const std::size_t count = scene->triangles.size();
        std::vector<std::uint32_t> ids;
        const RenderResult whole = gl->render(*scene, settings, compute_options(true), &ids);
        CHECK(counter(whole.stats, "triangle_batches") == 1.0);
        for (const std::size_t batch : {std::size_t{1}, std::size_t{1000}, count / 3 + 1}) {
            if (batch == 1 && count > 2000) continue;  // a dispatch per triangle: the small model only
            GlOptions options = compute_options(true);
            options.triangle_batch = batch;
            std::vector<std::uint32_t> batched_ids;
            const RenderResult batched = gl->render(*scene, settings, options, &batched_ids);
            INFO(scene->name, ", ", count, " triangles in batches of ", batch);
            CHECK(counter(batched.stats, "triangle_batches") == static_cast<double>((count + batch - 1) / batch));
            CHECK(counter(batched.stats, "gpu_buffer_bytes") < counter(whole.stats, "gpu_buffer_bytes"));
            CHECK(batched_ids == ids);
            CHECK(same_pixels(batched.image, whole.image));
        }
    }
}

// More triangles than one dispatch of 65,535 groups of 64 holds (the
// pipeline's old limit): 4,194,340, all but the last 100 behind the camera.
// The image and ids are those of the last 100 alone, their ids shifted.
TEST_CASE("gl compute pipeline: a scene of over 4.19 million triangles") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    Scene front;
    front.name = "quads";
    front.materials.push_back(Material{});
    for (int k = 0; k < 50; ++k) {  // 100 triangles: 50 small quads in a row, moving right
        const float x = -1.0f + 0.04f * static_cast<float>(k), y = 0.02f * static_cast<float>(k % 7) - 0.1f;
        add_quad(front, {x, y, -3.0f}, {x + 0.03f, y, -3.0f}, {x + 0.03f, y + 0.2f, -3.0f}, {x, y + 0.2f, -3.0f},
                 {0.02f, 0.0f, 0.0f}, 0);
    }
    REQUIRE(front.triangles.size() == 100);
    const std::size_t count = std::size_t{65535} * 64 + 100;
    Scene big = front;
    big.position_open.insert(big.position_open.end(), {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}});  // behind the camera
    big.position_close.insert(big.position_close.end(), {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
    const auto behind = static_cast<std::uint32_t>(big.position_open.size() - 3);
    big.triangles.assign(count - 100, glm::uvec3(behind, behind + 1, behind + 2));
    big.triangles.insert(big.triangles.end(), front.triangles.begin(), front.triangles.end());
    big.triangle_material.assign(count, 0);
    const RenderSettings settings = settings_for(64, 48, 4);
    std::vector<std::uint32_t> ids, front_ids;
    const RenderResult whole = gl->render(big, settings, compute_options(), &ids);
    const RenderResult alone = gl->render(front, settings, compute_options(), &front_ids);
    REQUIRE(ids.size() == front_ids.size());
    std::size_t differ = 0, shown = 0;
    for (std::size_t j = 0; j < ids.size(); ++j) {
        const std::uint32_t expected = front_ids[j] == no_triangle ? no_triangle : front_ids[j] + (count - 100);
        differ += ids[j] != expected ? 1 : 0;
        shown += front_ids[j] != no_triangle ? 1 : 0;
    }
    INFO(counter(whole.stats, "triangle_batches"), " batches");
    CHECK(shown > 100);
    CHECK(differ == 0);
    CHECK(same_pixels(whole.image, alone.image));
    CHECK(whole.stats.samples_hit == alone.stats.samples_hit);
}

namespace {

// The command in this process's own scratch folder.
CliRun run_cli(const std::string& arguments) {
    return run_cli_in(std::filesystem::temp_directory_path() / ("blurcull_gl_compute_test_" + std::to_string(::getpid())),
                      arguments);
}

}  // namespace

TEST_CASE("gl compute pipeline: --gl-pipeline on the command line, the JSON, the refusals") {
    if (renderer_or_skip() == nullptr) return;
    const CliRun run = run_cli("render --backend gl --gl-pipeline compute --occlusion off --scene hand --size 32x24 "
                            "--spp 4 --json -q -o hand_compute.png");
    INFO(run.err);
    REQUIRE(run.status == 0);
    const nlohmann::json summary = nlohmann::json::parse(run.out);
    CHECK(summary["backend"] == "gl");
    CHECK(summary["gl_pipeline"] == "compute");
    CHECK(summary["gl_renderer"].get<std::string>().find(", ") != std::string::npos);
    for (const char* phase : {"gpu_setup", "gpu_binning", "gpu_raster", "gpu_resolve"}) {
        CHECK(summary["ms_per_phase"].contains(phase));
    }
    CHECK(summary["counters"]["tile_list_retries"] == 0);
    const CliRun fragment = run_cli("render --backend gl --scene hand --size 32x24 --spp 4 --json -q -o hand_fragment.png");
    REQUIRE(fragment.status == 0);
    const nlohmann::json fragment_summary = nlohmann::json::parse(fragment.out);
    CHECK(fragment_summary["gl_pipeline"] == "fragment");
    CHECK(fragment_summary["samples_hit"] == summary["samples_hit"]);
    // dof-secondary's primary pass takes the compute pipeline too.
    const CliRun secondary = run_cli("render --backend gl --gl-pipeline compute --method dof-secondary "
                                     "--scene mirror-sphere --size 32x24 --spp 4 --layer-size 64 --json -q "
                                     "-o sphere_compute.png");
    INFO(secondary.err);
    REQUIRE(secondary.status == 0);
    const nlohmann::json secondary_summary = nlohmann::json::parse(secondary.out);
    CHECK(secondary_summary["gl_pipeline"] == "compute");
    CHECK(secondary_summary["secondary_rays"].get<double>() > 0);
    // Progress on stderr ("gl: N%", ending at 100%) once a render runs past a
    // second (on llvmpipe this one does; on a GPU it may end sooner, silently).
    const CliRun slow = run_cli("render --backend gl --gl-pipeline compute --scene car --size 96x72 --spp 16 "
                                "--json -o car_progress.png");
    REQUIRE(slow.status == 0);
    const double slow_ms = nlohmann::json::parse(slow.out)["ms_total"].get<double>();
    INFO("car 96x72 16 spp: ", slow_ms, " ms; stderr: ", slow.err);
    if (slow_ms > 1500.0) CHECK(slow.err.find("gl: 100%") != std::string::npos);
    if (slow_ms < 900.0) CHECK(slow.err.find("gl:") == std::string::npos);
    // One line each, naming the flag.
    for (const char* refused : {"render --backend gl --gl-pipeline compute --method interleave --size 32x24 -q",
                                "render --backend gl --gl-pipeline compute --gl-cell 4 --size 32x24 -q",
                                "render --backend gl --occlusion on --size 32x24 -q",
                                "render --backend cpu --gl-pipeline compute --size 32x24 -q",
                                "render --backend gl --gl-pipeline tiles --size 32x24 -q"}) {
        const CliRun bad = run_cli(refused);
        INFO(refused, ": ", bad.err);
        CHECK(bad.status != 0);
        const bool names_flag = bad.err.find("--gl-pipeline") != std::string::npos ||
                                bad.err.find("--gl-cell") != std::string::npos ||
                                bad.err.find("--occlusion") != std::string::npos;
        CHECK(names_flag);
    }
}

// The compute pipeline's sample counters are 64 bits a frame: the raster adds
// with BC_COUNTER_ADD (render_common.glsl), which counts a carry where the
// 32-bit word wraps, and SampleCounters reads word + 2^32 carry. Here the
// words start just below 2^32 and 1024 invocations add 1 and 3 to them
// (4.29 billion samples tested in one frame are out of llvmpipe's reach).
TEST_CASE("gl compute pipeline: the sample counters carry past 2^32") {
    GlRenderer* renderer = renderer_or_skip();
    if (renderer == nullptr) return;
    const blurcull::gl::HeadlessContext& context = renderer->context();
    context.make_current();
    const blurcull::gl::Functions& f = context.gl();
    static const char* const main_text = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; uint tested_carry; uint hit_carry; };
void main() {
    BC_COUNTER_ADD(tested, tested_carry, 1u)
    BC_COUNTER_ADD(hit, hit_carry, 3u)
}
)glsl";
    const blurcull::gl::Program program(
        f, {{GL_COMPUTE_SHADER,
             {blurcull::glsl::kernel_source(), blurcull::gl::embedded_source("gpu_layout_shared.h"),
              blurcull::gl::embedded_source("render_common.glsl"), main_text}}});
    SampleCounters counters(f);
    const std::uint32_t start[4] = {0xFFFFFF00u, 0xFFFFFFF0u, 0u, 0u};
    counters.preset(start);
    counters.bind_base(BC_GL_COUNTERS_BINDING);
    f.UseProgram(program.id());
    f.DispatchCompute(16, 1, 1);  // 1024 invocations
    f.UseProgram(0);
    RenderStats stats;
    counters.add_to(stats);
    CHECK(stats.samples_tested == 0xFFFFFF00ull + 1024ull);
    CHECK(stats.samples_hit == 0xFFFFFFF0ull + 3ull * 1024ull);
    RenderStats again;  // add_to resets every word, carries included
    counters.add_to(again);
    CHECK(again.samples_tested == 0);
    CHECK(again.samples_hit == 0);
}
