#include "render/gl/gl_compute_pipeline.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/cull_method.hpp"
#include "render/common/parallel_items.hpp"
#include "render/common/progress.hpp"
#include "render/common/render_method.hpp"
#include "render/common/surface_shading.hpp"
#include "render/gl/gl_alpha_mask.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_frame_common.hpp"
#include "render/gl/gl_phase_timers.hpp"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"
#include "scene/scene_checks.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <future>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::frontend {

using gl::shader_stage;

struct GlComputePrograms {
    gl::Program setup;
    gl::Program strata;
    gl::Program bin;
    gl::Program scan;
    gl::Program raster;
    gl::Program resolve;
    // The entries the last frame's tile lists needed (0 before the first):
    // the next frame's starting capacity, a quarter more.
    std::size_t needed_entries = 0;

    explicit GlComputePrograms(const gl::Functions& gl)
        : setup(gl, {shader_stage(GL_COMPUTE_SHADER, "render_setup.comp")}),
          strata(gl, {shader_stage(GL_COMPUTE_SHADER, "render_compute_strata.comp")}),
          bin(gl, {shader_stage(GL_COMPUTE_SHADER, "render_compute_bin.comp")}),
          scan(gl, {shader_stage(GL_COMPUTE_SHADER, "render_compute_scan.comp")}),
          raster(gl, {shader_stage(GL_COMPUTE_SHADER, "render_compute_raster.comp", gl::Prelude::render_masked)}),
          resolve(gl, {shader_stage(GL_COMPUTE_SHADER, "render_resolve.comp")}) {}
};

namespace {

using gpu::TileBinState;
using gpu::TriangleInfo;
constexpr int tile_size = BC_GL_TILE_SIZE;
// render_compute_raster.comp's CHUNK: samples per pixel a raster dispatch tests.
constexpr std::uint32_t raster_chunk = 8;
// List entries a raster dispatch takes per tile on a software renderer:
// llvmpipe ends a shader invocation's loops after 65535 iterations in all
// (gallivm's loop limiter), silently: 64 entries (one batch) of 8 samples
// stay below it (at most ~300 iterations an entry: a 24-edge hull, 8 samples).
constexpr std::uint32_t software_slice_entries = 64;

// The phases GlPhaseTimers times, in ms_per_phase's order.
enum Phase : std::size_t { setup_phase, binning_phase, raster_phase, resolve_phase };
std::vector<std::string> phase_names() { return {"setup", "binning", "raster", "resolve"}; }

void check_compute_request(const Scene& scene, const RenderSettings& settings) {
    validate_settings(settings);
    require_valid_scene(scene);
    if (settings.method != RenderMethod::stochastic) {
        throw std::invalid_argument(std::string("gl: the compute pipeline renders the stochastic method only (method ") +
                                    to_string(settings.method) + ")");
    }
    // Sample ids hold a scene index below no_triangle (the background).
    if (scene.triangles.size() >= no_triangle) {
        throw gl::GlError("gl: " + std::to_string(scene.triangles.size()) +
                          " triangles exceed the compute pipeline's limit of " + std::to_string(no_triangle - 1));
    }
}

// The GL's largest shader storage block, in bytes.
std::size_t storage_block_limit(const gl::Functions& gl) {
    return static_cast<std::size_t>(static_cast<unsigned>(get_integer(gl, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)));
}

// Triangles per batch: GlOptions::triangle_batch, or 2^20 (~700 MiB of
// per-batch buffers, docs/gl-backend.md); at most as many TriangleInfos (the
// largest per-triangle record) as a storage block holds (llvmpipe: 128 MiB,
// ~289,000), and one invocation per triangle in at most 65535 work groups
// of 64 (GL's guaranteed dispatch size).
std::size_t batch_size(const gl::Functions& gl, const GlOptions& options) {
    constexpr std::size_t dispatch_limit = std::size_t{65535} * 64;
    const std::size_t wanted = options.triangle_batch > 0 ? options.triangle_batch : std::size_t{1} << 20;
    const std::size_t block_limit = std::max<std::size_t>(storage_block_limit(gl) / sizeof(TriangleInfo), 1);
    return std::min({wanted, dispatch_limit, block_limit});
}

// A storage buffer of `bytes`, refused in one line when it exceeds the GL's
// largest shader storage block.
gl::Buffer bounded_buffer(const gl::Functions& gl, std::size_t bytes, const char* what) {
    const std::size_t limit = storage_block_limit(gl);
    if (bytes > limit) {
        throw gl::GlError("gl: the compute pipeline's " + std::string(what) + " need " + std::to_string(bytes >> 20) +
                          " MiB, more than the GL's largest storage block (" + std::to_string(limit >> 20) + " MiB)");
    }
    return storage_buffer(gl, std::max<std::size_t>(bytes, 4));
}

// One frame: the per-sample buffers live through it; the per-triangle ones
// hold one batch of at most `batch` triangles (load_batch), which is set up,
// binned and rasterized before the next; the samples carry the winners over.
class ComputeFrame {
public:
    // `flat`: each triangle's flat colour (the render's SurfaceShader).
    ComputeFrame(const gl::Functions& gl, GlComputePrograms& programs, const Scene& scene,
                 const RenderSettings& settings, std::size_t batch, const std::vector<glm::vec3>& flat)
        : gl_(gl),
          programs_(programs),
          scene_(scene),
          settings_(settings),
          model_(scene.camera, settings.width, settings.height),
          batch_capacity_(std::max<std::size_t>(std::min(batch, scene.triangles.size()), 1)),
          pixels_(static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height)),
          tiles_x_(static_cast<std::uint32_t>((settings.width + tile_size - 1) / tile_size)),
          tiles_y_(static_cast<std::uint32_t>((settings.height + tile_size - 1) / tile_size)),
          tiles_(static_cast<std::size_t>(tiles_x_) * tiles_y_),
          triangle_buffer_(bounded_buffer(gl_, batch_capacity_ * sizeof(gpu::GpuMovingTriangle), "triangles")),
          info_buffer_(bounded_buffer(gl_, batch_capacity_ * sizeof(TriangleInfo), "triangle infos")),
          class_buffer_(bounded_buffer(gl_, batch_capacity_ * sizeof(std::int32_t), "triangle classes")),
          counters_(gl_),
          colour_buffer_(storage_buffer(gl_, frame_colours(flat, scene))),
          sum_buffer_(bounded_buffer(gl_, pixels_ * sizeof(glm::vec4), "pixel sums")),
          id_buffer_(bounded_buffer(gl_, pixels_ * static_cast<std::size_t>(settings.spp) * sizeof(std::uint32_t),
                                    "sample ids")),
          key_buffer_(bounded_buffer(gl_, pixels_ * static_cast<std::size_t>(settings.spp) * sizeof(float),
                                     "sample depth keys")),
          stratum_buffer_(
              bounded_buffer(gl_, batch_capacity_ * BC_GL_TIME_STRATA * sizeof(glm::vec4), "stratum boxes")),
          tile_count_buffer_(storage_buffer(gl_, tiles_ * sizeof(std::uint32_t))),
          tile_end_buffer_(storage_buffer(gl_, tiles_ * sizeof(std::uint32_t))),
          state_buffer_(storage_buffer(gl_, sizeof(TileBinState))),
          mask_(gl_, scene) {}

    // The scene's triangles first ... first + count - 1 (count at most the
    // batch size), made on the host as the fragment pipeline's
    // (frame_triangles): no GL call, so it may run on another thread while
    // the GPU works on the batch before.
    FrameTriangles prepare_batch(std::size_t first, std::size_t count) const {
        return frame_triangles(scene_, model_, false, first, count, render_threads(settings_));
    }

    // That batch into the per-triangle buffers.
    void load_batch(std::size_t first, std::size_t count, const FrameTriangles& batch) {
        triangle_buffer_.write(batch.gpu.data(), batch.gpu.size() * sizeof(gpu::GpuMovingTriangle));
        class_buffer_.write(batch.classes.data(), batch.classes.size() * sizeof(std::int32_t));
        first_ = first;
        count_ = count;
    }

    // The bytes of every buffer the frame holds now (the tile lists at their
    // current capacity): what it needs of GPU memory, less the programs.
    std::size_t buffer_bytes() const {
        std::size_t bytes = mask_.buffer_bytes();  // and the counters' 16
        for (const gl::Buffer* buffer :
             {&triangle_buffer_, &info_buffer_, &class_buffer_, &colour_buffer_, &sum_buffer_, &id_buffer_,
              &key_buffer_, &stratum_buffer_, &tile_count_buffer_, &tile_end_buffer_, &state_buffer_}) {
            bytes += buffer->size();
        }
        return bytes + (list_buffer_ ? list_buffer_->size() : 0);
    }

    // render_setup.comp: each triangle's screen bound, pixel rectangle, path;
    // render_compute_strata.comp: its shutter slices' screen boxes.
    void run_setup(bool time_strata, GlPhaseTimers& timers) {
        bind_common();
        timers.begin(setup_phase);
        if (count_ > 0) {
            set_common(gl_, programs_.setup, model_, settings_, 0);
            set_int(gl_, programs_.setup, "triangle_count", static_cast<int>(count_));
            set_int(gl_, programs_.setup, "method", kernel_cull_method(settings_.cull));
            set_int(gl_, programs_.setup, "force_full", 0);
            gl_.DispatchCompute(groups(count_, 64), 1, 1);
            gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            set_common(gl_, programs_.strata, model_, settings_, 0);
            set_int(gl_, programs_.strata, "triangle_count", static_cast<int>(count_));
            set_int(gl_, programs_.strata, "time_strata", time_strata ? 1 : 0);
            gl_.DispatchCompute(groups(count_, 64), 1, 1);
            gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        timers.end(setup_phase);
    }

    // Binning: count, prefix sum, then (the lists grown first when the scan
    // found them longer than `capacity`: counted in `retries`) the fill.
    TileBinState run_binning(std::size_t& capacity, int& retries, GlPhaseTimers& timers) {
        reserve_lists(capacity);
        bind_common();
        timers.begin(binning_phase);
        gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, tile_count_buffer_.id());
        gl_.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        write_state(capacity);
        if (count_ > 0) dispatch_bin(0);
        set_common(gl_, programs_.scan, model_, settings_, 0);
        set_uint(gl_, programs_.scan, "tile_count", static_cast<std::uint32_t>(tiles_));
        gl_.DispatchCompute(1, 1, 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        timers.end(binning_phase);
        TileBinState state{};
        state_buffer_.read(&state, sizeof state);
        if (state.entries_high != 0) {
            throw gl::GlError("gl: the compute pipeline's tile lists need more than 2^32 entries");
        }
        if (state.overflow != 0) {
            // Found before anything was written: the lists get room for all.
            capacity = state.entries;
            ++retries;
            reserve_lists(capacity);
            list_buffer_->bind_base(BC_GL_TILE_LIST_BINDING);
            state.capacity = static_cast<std::uint32_t>(capacity);
            state.overflow = 0;
            gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, state_buffer_.id());
            gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof state, &state);
            gl_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        }
        timers.begin(binning_phase);
        if (count_ > 0) dispatch_bin(1);
        timers.end(binning_phase);
        gl::check_gl(gl_, "gl: compute binning");
        return state;
    }

    // The raster pass over the loaded batch: a dispatch per chunk of samples
    // and slice of the lists (slice_entries of them; the lists are at most
    // max_count long). The first batch starts every sample at the background.
    // `progress` gets `units` advances over the pass: after each
    // dispatch where `finish_each` (software GL, whose dispatches are slow
    // and a glFinish cheap), else all at the end (the caller's read of the
    // bin state waits for the GPU).
    void run_raster(std::uint32_t max_count, std::uint32_t slice_entries, bool occlusion, GlPhaseTimers& timers,
                    Progress& progress, int units, bool finish_each) {
        timers.begin(raster_phase);
        set_common(gl_, programs_.raster, model_, settings_, 0);
        set_int(gl_, programs_.raster, "method", kernel_cull_method(settings_.cull));
        set_int(gl_, programs_.raster, "tile_bounds", cull_method_info(settings_.cull).bounds_samples ? 1 : 0);
        set_uint(gl_, programs_.raster, "tiles_x", tiles_x_);
        set_uint(gl_, programs_.raster, "slice_entries", slice_entries);
        set_int(gl_, programs_.raster, "occlusion", occlusion ? 1 : 0);
        set_uint(gl_, programs_.raster, "triangle_base", static_cast<std::uint32_t>(first_));
        const auto spp = static_cast<std::uint32_t>(settings_.spp);
        const std::uint64_t slices =
            max_count == 0 ? 1 : (std::uint64_t{max_count} + slice_entries - 1) / slice_entries;
        const std::uint64_t dispatches = slices * ((spp + raster_chunk - 1) / raster_chunk);
        std::uint64_t done = 0;
        int advanced = 0;
        for (std::uint32_t chunk = 0; chunk < spp; chunk += raster_chunk) {
            set_uint(gl_, programs_.raster, "chunk_base", chunk);
            // At least one slice: the first starts every sample at the background.
            for (std::uint32_t first = 0; first == 0 || first < max_count; first += slice_entries) {
                set_uint(gl_, programs_.raster, "slice_first", first);
                set_int(gl_, programs_.raster, "carry", first > 0 || first_ > 0 ? 1 : 0);
                gl_.DispatchCompute(tiles_x_, tiles_y_, 1);
                gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
                ++done;
                if (finish_each) {
                    gl_.Finish();
                    const auto due = static_cast<int>(static_cast<std::uint64_t>(units) * done / dispatches);
                    for (; advanced < due; ++advanced) progress.advance();
                }
            }
        }
        for (; advanced < units; ++advanced) progress.advance();
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        timers.end(raster_phase);
        gl::check_gl(gl_, "gl: compute raster");
    }

    // The bin state after the frame: overflow 2 if the fill found no room.
    TileBinState final_state() const {
        TileBinState state{};
        state_buffer_.read(&state, sizeof state);
        return state;
    }

    // render_resolve.comp over every sample's id, in sample order.
    void run_resolve(GlPhaseTimers& timers, RenderStats& stats) {
        timers.begin(resolve_phase);
        set_common(gl_, programs_.resolve, model_, settings_, 0);
        set_uint(gl_, programs_.resolve, "background", static_cast<std::uint32_t>(scene_.triangles.size()));
        set_int(gl_, programs_.resolve, "keep_ids", 0);
        set_int(gl_, programs_.resolve, "ids_in_buffer", 1);
        set_int(gl_, programs_.resolve, "pass_ids", BC_GL_PASS_IDS_UNIT);
        gl_.DispatchCompute(groups(static_cast<std::size_t>(settings_.width), 8),
                            groups(static_cast<std::size_t>(settings_.height), 8), 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        timers.end(resolve_phase);
        counters_.add_to(stats);
        gl::check_gl(gl_, "gl: compute resolve");
    }

    Image read_back(std::vector<std::uint32_t>* sample_ids) const {
        Image image = image_from_sums(sum_buffer_, settings_);
        if (sample_ids != nullptr) {
            sample_ids->assign(pixels_ * static_cast<std::size_t>(settings_.spp), no_triangle);
            id_buffer_.read(sample_ids->data(), sample_ids->size() * sizeof(std::uint32_t));
        }
        gl::check_gl(gl_, "gl: compute readback");
        return image;
    }

    // A first capacity: at least 4 entries per triangle of a batch and one per tile.
    std::size_t default_capacity() const { return std::max<std::size_t>(4 * batch_capacity_, tiles_); }

private:
    // Tile lists of at least `capacity` entries: the batch before's when they
    // hold that many, else new ones.
    void reserve_lists(std::size_t capacity) {
        const std::size_t bytes = std::max<std::size_t>(capacity, 1) * sizeof(std::uint32_t);
        if (!list_buffer_ || list_buffer_->size() < bytes) {
            list_buffer_.reset();
            list_buffer_.emplace(bounded_buffer(gl_, bytes, "tile lists"));
        }
    }

    void write_state(std::size_t capacity) const {
        TileBinState start{};
        start.capacity = static_cast<std::uint32_t>(capacity);
        gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, state_buffer_.id());
        gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof start, &start);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    void dispatch_bin(int fill) const {
        set_common(gl_, programs_.bin, model_, settings_, 0);
        set_int(gl_, programs_.bin, "triangle_count", static_cast<int>(count_));
        set_int(gl_, programs_.bin, "fill", fill);
        set_uint(gl_, programs_.bin, "tiles_x", tiles_x_);
        gl_.DispatchCompute(groups(count_, 64), 1, 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }

    static GLuint groups(std::size_t items, std::size_t per_group) {
        return static_cast<GLuint>((items + per_group - 1) / per_group);
    }

    // Binding points are context state, and the fragment passes use the
    // same numbers for other buffers: bound before each run.
    void bind_common() const {
        mask_.bind();
        triangle_buffer_.bind_base(BC_GL_TRIANGLES_BINDING);
        info_buffer_.bind_base(BC_GL_INFOS_BINDING);
        counters_.bind_base(BC_GL_COUNTERS_BINDING);
        colour_buffer_.bind_base(BC_GL_COLOURS_BINDING);
        sum_buffer_.bind_base(BC_GL_SUMS_BINDING);
        id_buffer_.bind_base(BC_GL_SAMPLE_IDS_BINDING);
        key_buffer_.bind_base(BC_GL_SAMPLE_KEYS_BINDING);
        stratum_buffer_.bind_base(BC_GL_STRATUM_BOXES_BINDING);
        class_buffer_.bind_base(BC_GL_CLASSES_BINDING);
        tile_count_buffer_.bind_base(BC_GL_TILE_COUNTS_BINDING);
        tile_end_buffer_.bind_base(BC_GL_TILE_ENDS_BINDING);
        state_buffer_.bind_base(BC_GL_TILE_STATE_BINDING);
        if (list_buffer_) list_buffer_->bind_base(BC_GL_TILE_LIST_BINDING);
    }

    const gl::Functions& gl_;
    GlComputePrograms& programs_;
    const Scene& scene_;
    const RenderSettings& settings_;
    CameraModel model_;
    std::size_t batch_capacity_, pixels_;
    std::uint32_t tiles_x_, tiles_y_;
    std::size_t tiles_;
    std::size_t first_ = 0, count_ = 0;  // the loaded batch
    gl::Buffer triangle_buffer_, info_buffer_, class_buffer_;
    SampleCounters counters_;
    gl::Buffer colour_buffer_, sum_buffer_, id_buffer_, key_buffer_, stratum_buffer_;
    gl::Buffer tile_count_buffer_, tile_end_buffer_, state_buffer_;
    GlAlphaMask mask_;
    std::optional<gl::Buffer> list_buffer_;
};

}  // namespace

RenderResult render_gl_compute(const gl::HeadlessContext& context, std::shared_ptr<GlComputePrograms>& programs,
                               const Scene& scene, const RenderSettings& settings, const GlOptions& options,
                               std::vector<std::uint32_t>* sample_ids) {
    const RenderClock::time_point start = RenderClock::now();
    check_compute_request(scene, settings);
    const gl::Functions& gl = context.gl();
    if (!programs) programs = std::make_shared<GlComputePrograms>(gl);

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = scene.triangles.size();
    RenderClock::time_point phase = RenderClock::now();
    // Per-hit shading (textures, vertex colours, normals) on the host from the
    // winners, as the fragment pipeline does (GlRenderer::render).
    const CameraModel model(scene.camera, settings.width, settings.height);
    const SurfaceShader shader(scene, model, render_threads(settings));
    std::vector<std::uint32_t> winners;
    const bool keep_ids = (options.keep_sample_ids && sample_ids != nullptr) || shader.any_per_hit();
    std::vector<std::uint32_t>* kept_ids = options.keep_sample_ids && sample_ids != nullptr ? sample_ids : &winners;
    GlPhaseTimers timers(gl, phase_names());
    const std::size_t count = scene.triangles.size();
    const std::size_t batch = batch_size(gl, options);
    ComputeFrame frame(gl, *programs, scene, settings, batch, shader.flat_colours());
    std::size_t capacity = options.tile_list_capacity > 0
                               ? options.tile_list_capacity
                               : std::max(frame.default_capacity(),
                                          programs->needed_entries + programs->needed_entries / 4);
    // Summed or the largest over the batches.
    int retries = 0;
    std::size_t batches = 0, needed = 0, peak_bytes = 0;
    // "gl: N%" on stderr past a second: 100 steps per batch's raster (one
    // per batch when there are many).
    const std::size_t batch_count = std::max<std::size_t>((count + batch - 1) / batch, 1);
    const int units = batch_count > 1000 ? 1 : 100;
    const int steps = static_cast<int>(std::min<std::size_t>(batch_count, std::size_t{1} << 30)) * units;
    Progress progress(settings.progress, start, steps, "gl");
    double entries = 0.0, occluded = 0.0, setup_ms = 0.0, raster_ms = 0.0;
    std::uint32_t longest = 0, slice = 0;
    // The next batch is made on the host while the GPU works on this one.
    auto batch_size_at = [&](std::size_t first) { return std::min(batch, count - first); };
    std::future<FrameTriangles> next;
    for (std::size_t first = 0; first == 0 || first < count; first += batch) {
        phase = RenderClock::now();
        const FrameTriangles current = next.valid() ? next.get() : frame.prepare_batch(first, batch_size_at(first));
        if (first + batch < count) {
            next = std::async(std::launch::async,
                              [&frame, at = first + batch, n = batch_size_at(first + batch)] {
                                  return frame.prepare_batch(at, n);
                              });
        }
        frame.load_batch(first, batch_size_at(first), current);
        frame.run_setup(options.time_strata, timers);
        setup_ms += ms_since(phase);

        phase = RenderClock::now();
        const TileBinState state = frame.run_binning(capacity, retries, timers);
        slice = context.software() ? software_slice_entries : std::max<std::uint32_t>(state.max_count, 1);
        frame.run_raster(state.max_count, slice, options.occlusion, timers, progress, units, context.software());
        const TileBinState final_state = frame.final_state();
        if (final_state.overflow != 0) {
            throw gl::GlError("gl: the compute pipeline's tile lists overflowed after they were sized");
        }
        raster_ms += ms_since(phase);
        ++batches;
        needed = std::max<std::size_t>(needed, state.entries);
        entries += state.entries;
        occluded += final_state.occluded;
        longest = std::max(longest, state.max_count);
        peak_bytes = std::max(peak_bytes, frame.buffer_bytes());
    }
    progress.finish();
    if (options.tile_list_capacity == 0) programs->needed_entries = needed;
    stats.ms_per_phase.emplace_back("setup", setup_ms);
    phase = RenderClock::now();
    frame.run_resolve(timers, stats);
    stats.ms_per_phase.emplace_back("raster+resolve", raster_ms + ms_since(phase));

    phase = RenderClock::now();
    result.image = frame.read_back(keep_ids ? kept_ids : nullptr);
    if (shader.any_per_hit()) result.image = resolve_sample_ids(shader, model, settings, *kept_ids);
    stats.ms_per_phase.emplace_back("readback", ms_since(phase));
    timers.add_to(stats);
    stats.counters.emplace_back("triangle_batches", static_cast<double>(batches));
    stats.counters.emplace_back("gpu_buffer_bytes", static_cast<double>(peak_bytes));
    stats.counters.emplace_back("tile_list_entries", entries);
    stats.counters.emplace_back("tile_list_capacity", static_cast<double>(capacity));
    stats.counters.emplace_back("tile_list_retries", static_cast<double>(retries));
    stats.counters.emplace_back("tile_list_longest", static_cast<double>(longest));
    stats.counters.emplace_back("raster_slice_entries", static_cast<double>(slice));
    stats.counters.emplace_back("occluded_entries", occluded);
    stats.ms_total = ms_since(start);
    return result;
}

}  // namespace blurcull::frontend
