#include "render/gl/gl_layer_images.hpp"

#include "render/gl/gl_layer_shared.h"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <cstddef>
#include <cstring>
#include <string>

namespace blurcull::frontend {
namespace {

// The kernel's GLSL, the bindings, the rasterizing arithmetic shared with
// the host, the passes' std430 structs, then the main.
gl::ShaderStage layer_stage(GLenum type, std::string_view main_name,
                            gl::Prelude prelude = gl::Prelude::layers) {
    return gl::shader_stage(type, main_name, prelude);
}

// SSBO bindings of the passes (gpu_layout_shared.h): each also the index of
// its buffer in Passes::buffers.
enum Binding : GLuint {
    triangles_binding = BC_GL_LAYER_TRIANGLES_BINDING,
    pass_binding = BC_GL_LAYER_PASS_BINDING,
    own_binding = BC_GL_LAYER_OWN_BINDING,
    fans_binding = BC_GL_LAYER_FANS_BINDING,
    counts_binding = BC_GL_LAYER_COUNTS_BINDING,
    layer_depth_binding = BC_GL_LAYER_DEPTH_BINDING,
    layer_triangle_binding = BC_GL_LAYER_TRIANGLE_IDS_BINDING,
    cluster_depth_binding = BC_GL_LAYER_CLUSTER_DEPTH_BINDING,
    origins_binding = BC_GL_LAYER_ORIGINS_BINDING,
    pyramid_binding = BC_GL_LAYER_PYRAMID_BINDING,
    texel_count_binding = BC_GL_LAYER_TEXEL_COUNTS_BINDING,
};

void fill_words(const gl::Functions& f, const gl::Buffer& buffer, std::uint32_t value) {
    f.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer.id());
    f.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    f.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

GLuint groups_of(std::size_t items, std::size_t group) { return static_cast<GLuint>((items + group - 1) / group); }

// The cluster's ray origins for the in-front cull: gathered on the GPU, or
// the host's (none: no such cull).
std::size_t origin_count(const GlLayerInput& input) {
    if (input.origin_points != nullptr) return input.origin_count;
    return input.origins != nullptr ? input.origins->size() : 0;
}

gpu::LayerPass pass_of(const kernelf::LayerView& view, int layers, std::size_t triangles, std::size_t origins,
                       float normal_threshold) {
    gpu::LayerPass pass;
    pass.eye = glm::vec4(view.eye, 0.0f);
    pass.forward = glm::vec4(view.forward, 0.0f);
    pass.right = glm::vec4(view.right, 0.0f);
    pass.up = glm::vec4(view.up, 0.0f);
    pass.frustum = glm::vec4(view.tan_half_fov, view.near, view.far, normal_threshold);
    pass.sizes = glm::ivec4(view.size, layers, static_cast<int>(triangles), static_cast<int>(origins));
    return pass;
}

// The pyramid's level sizes, base first, down to 1.
std::vector<int> level_sizes(int size) {
    std::vector<int> sizes{size};
    while (sizes.back() > 1) sizes.push_back((sizes.back() + 1) / 2);
    return sizes;
}

}  // namespace

struct GlLayerBuilder::Passes {
    gl::Program setup, draw, raster, cluster_depth, pyramid;
    gl::VertexArray vertex_array;
    // The buffers, by binding (Binding), kept from one cluster to the next.
    std::array<std::optional<gl::Buffer>, BC_GL_LAYER_BINDINGS> buffers;

    // Binding's buffer with room for `bytes` (`data` copied in), bound.
    const gl::Buffer& buffer(const gl::Functions& f, Binding binding, std::size_t bytes, const void* data = nullptr) {
        const gl::Buffer& b = gl::reserve_storage(f, buffers[binding], bytes, data);
        b.bind_base(binding);
        return b;
    }
    const gl::Buffer& at(Binding binding) const { return *buffers[binding]; }

    void upload(const gl::Functions& f, const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                std::size_t pyramid_floats, bool with_triangles);
    void upload_triangles(const gl::Functions& f, const std::vector<std::array<glm::vec3, 3>>& vertices,
                          const std::vector<glm::vec3>& normals);
    GlLayerCounts counts(const gl::Functions& f) const;
    void reset_counts(const gl::Functions& f);
    void reset_cluster_counts();
    void make_fans(const gl::Functions& f, const GlLayerInput& input);
    void draw_fans(const gl::Functions& f, int size);
    void raster_fans(const gl::Functions& f, std::size_t triangles);
    void make_pyramid(const gl::Functions& f, int size);
    GlClusterLayers read_back(const gl::Functions& f, int size, int layers, std::size_t pyramid_floats) const;
};

// Every count to 0 (the counts buffer made where there is none).
void GlLayerBuilder::Passes::reset_counts(const gl::Functions& f) {
    const std::uint32_t zero[BC_LAYER_COUNTS] = {};
    buffer(f, counts_binding, sizeof zero, zero);
}

// The counts of one cluster's passes: its fans, and the draws' command (its
// one instance); the others add up over the clusters.
void GlLayerBuilder::Passes::reset_cluster_counts() {
    const std::uint32_t cluster[BC_LAYERS_COUNT_PER_CLUSTER] = {0, 0, 1, 0, 0};
    at(counts_binding).write(cluster, sizeof cluster, BC_LAYER_COUNT_FANS * sizeof(std::uint32_t));
    at(counts_binding).bind_base(counts_binding);
}

// The scene's triangles (world space) and unit normals into their buffer.
void GlLayerBuilder::Passes::upload_triangles(const gl::Functions& f,
                                              const std::vector<std::array<glm::vec3, 3>>& vertices,
                                              const std::vector<glm::vec3>& normals) {
    std::vector<gpu::LayerTriangle> packed(vertices.size());
    for (std::size_t t = 0; t < vertices.size(); ++t)
        packed[t] = gpu::LayerTriangle{glm::vec4(vertices[t][0], 0.0f), glm::vec4(vertices[t][1], 0.0f),
                                       glm::vec4(vertices[t][2], 0.0f), glm::vec4(normals[t], 0.0f)};
    buffer(f, triangles_binding, packed.size() * sizeof(gpu::LayerTriangle), packed.data());
}

// The cluster's culls and view into their buffers (and the scene's
// triangles `with_triangles`, else kept from upload_triangles); the
// k-buffer, triangle ids, cluster depth and texel counts cleared.
void GlLayerBuilder::Passes::upload(const gl::Functions& f, const kernelf::LayerView& view, int layers,
                                    const GlLayerInput& input, std::size_t pyramid_floats, bool with_triangles) {
    const std::size_t triangles = input.vertices->size();
    const bool gathered = input.origin_points != nullptr;
    const std::size_t origins = origin_count(input);
    const std::size_t plane = static_cast<std::size_t>(view.size) * static_cast<std::size_t>(view.size);
    const std::size_t own_words = (triangles + 31) / 32;
    std::vector<std::uint32_t> own_bits(input.own_source != nullptr ? 0 : own_words, 0u);
    for (std::size_t t = 0; t < triangles && !own_bits.empty(); ++t)
        if ((*input.own)[t] != 0) own_bits[t / 32] |= 1u << (t % 32);
    std::vector<glm::vec4> origin_points(gathered ? 0 : origins);
    for (std::size_t i = 0; i < origin_points.size(); ++i) origin_points[i] = glm::vec4((*input.origins)[i], 0.0f);
    const gpu::LayerPass pass = pass_of(view, layers, triangles, origins, input.normal_threshold);
    if (with_triangles) {
        upload_triangles(f, *input.vertices, *input.normals);
    } else {
        if (!buffers[triangles_binding] || buffers[triangles_binding]->size() < triangles * sizeof(gpu::LayerTriangle))
            throw gl::GlError("gl: build_resident before upload_triangles of the scene's " + std::to_string(triangles) +
                              " triangles");
        at(triangles_binding).bind_base(triangles_binding);
    }
    const gl::Buffer& pass_buffer = buffer(f, pass_binding, sizeof pass, &pass);
    if (input.threshold_source != nullptr)
        gl::copy_buffer(f, *input.threshold_source, input.threshold_offset, pass_buffer,
                        offsetof(gpu::LayerPass, frustum) + 3 * sizeof(float), sizeof(float));
    if (input.own_source != nullptr)
        gl::copy_buffer(f, *input.own_source, input.own_offset,
                        buffer(f, own_binding, own_words * sizeof(std::uint32_t)), 0, own_words * sizeof(std::uint32_t));
    else
        buffer(f, own_binding, own_bits.size() * sizeof(std::uint32_t), own_bits.data());
    buffer(f, fans_binding, 2 * triangles * sizeof(gpu::LayerFan));
    // build_resident's counts add up from upload_triangles on; build's are its own.
    if (with_triangles) reset_counts(f);
    reset_cluster_counts();
    if (gathered) {
        input.origin_points->bind_base(origins_binding);
        input.origin_indices->bind_base(BC_GL_LAYER_ORIGIN_INDICES_BINDING);
    } else {
        buffer(f, origins_binding, origin_points.size() * sizeof(glm::vec4), origin_points.data());
    }
    buffer(f, pyramid_binding, pyramid_floats * sizeof(float));
    const std::size_t texels = plane * static_cast<std::size_t>(layers);
    fill_words(f, buffer(f, layer_depth_binding, texels * sizeof(std::uint32_t)), BC_LAYER_EMPTY);
    fill_words(f, buffer(f, layer_triangle_binding, texels * sizeof(std::uint32_t)), 0xFFFFFFFFu);
    fill_words(f, buffer(f, cluster_depth_binding, plane * sizeof(std::uint32_t)), BC_LAYER_EMPTY);
    fill_words(f, buffer(f, texel_count_binding, plane * sizeof(std::uint32_t)), 0u);
}

// The cluster's depth map and the fans, with the draws' indirect command
// (no wait for their count: the draws and the compute scan read it).
void GlLayerBuilder::Passes::make_fans(const gl::Functions& f, const GlLayerInput& input) {
    const std::size_t triangles = input.vertices->size();
    const std::size_t origins = origin_count(input);
    if (origins > 0) {
        f.UseProgram(cluster_depth.id());
        f.Uniform1i(f.GetUniformLocation(cluster_depth.id(), "gathered"), input.origin_points != nullptr ? 1 : 0);
        gl::dispatch_in_rows(f, groups_of(origins, 64));
    }
    if (triangles > 0) {
        f.UseProgram(setup.id());
        f.DispatchCompute(groups_of(triangles, 64), 1, 1);
    }
    // The scans read the fans and their count; the draws take it as their indirect command.
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

// The two scans of the fans in compute (GlLayerRaster::compute): depths
// into the k-buffer, then their triangles. A work group per fan the setup
// pass can write (two per scene triangle), in rows of at most 65,535 groups
// (GL's least maximum); those past the fans written return at once.
void GlLayerBuilder::Passes::raster_fans(const gl::Functions& f, std::size_t triangles) {
    const std::size_t fans = 2 * triangles;
    if (fans == 0) return;
    f.UseProgram(raster.id());
    const GLint peel_pass = f.GetUniformLocation(raster.id(), "peel_pass");
    for (int peel = 0; peel < 2; ++peel) {
        f.Uniform1i(peel_pass, peel);
        gl::dispatch_in_rows(f, fans);
        f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

// The two scans of the fans on the GL rasterizer (GlLayerRaster::graphics):
// depths into the k-buffer, then their triangles; each of the fans the setup
// pass counted into the counts buffer's draw command.
void GlLayerBuilder::Passes::draw_fans(const gl::Functions& f, int size) {
    const gl::Texture target(f, GL_TEXTURE_2D, GL_R8, size, size);  // never written: the shader has no output
    const gl::Framebuffer framebuffer(f);
    f.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    f.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.id(), 0);
    if (f.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw gl::GlError("gl: the layer pass's framebuffer is incomplete");
    f.Viewport(0, 0, size, size);
    f.Disable(GL_DEPTH_TEST);
    f.Disable(GL_CULL_FACE);
    f.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    f.UseProgram(draw.id());
    f.BindVertexArray(vertex_array.id());
    const GLint peel_pass = f.GetUniformLocation(draw.id(), "peel_pass");
    f.BindBuffer(GL_DRAW_INDIRECT_BUFFER, at(counts_binding).id());
    const auto command = reinterpret_cast<const void*>(std::uintptr_t{BC_LAYER_COUNT_DRAW * sizeof(std::uint32_t)});
    for (int peel = 0; peel < 2; ++peel) {
        f.Uniform1i(peel_pass, peel);
        f.DrawArraysIndirect(GL_TRIANGLES, command);
        f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    f.BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    f.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    f.BindVertexArray(0);
    f.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

// The pyramid: levels 0 and 1 from the layers, then the rest in one workgroup.
void GlLayerBuilder::Passes::make_pyramid(const gl::Functions& f, int size) {
    const GLuint program = pyramid.id();
    f.UseProgram(program);
    f.Uniform1i(f.GetUniformLocation(program, "base_size"), size);
    f.Uniform1i(f.GetUniformLocation(program, "from_layers"), 1);
    const GLuint groups = groups_of(static_cast<std::size_t>((size + 1) / 2), 16);
    f.DispatchCompute(groups, groups, 1);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    f.Uniform1i(f.GetUniformLocation(program, "from_layers"), 0);
    f.DispatchCompute(1, 1, 1);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    f.UseProgram(0);
}

GlClusterLayers GlLayerBuilder::Passes::read_back(const gl::Functions& f, int size, int layers,
                                                  std::size_t pyramid_floats) const {
    gl::check_gl(f, "dof-secondary: the layer passes");
    const std::size_t texels = static_cast<std::size_t>(size) * static_cast<std::size_t>(size) *
                               static_cast<std::size_t>(layers);
    GlClusterLayers out;
    out.size = size;
    out.layers = layers;
    out.depth.resize(texels);
    at(layer_depth_binding).read(out.depth.data(), texels * sizeof(float));  // the bits are the floats
    out.triangle.resize(texels);
    at(layer_triangle_binding).read(out.triangle.data(), texels * sizeof(std::uint32_t));
    for (std::uint32_t& id : out.triangle)
        if (id == 0xFFFFFFFFu) id = 0;  // no surface: the host's default
    out.pyramid.resize(pyramid_floats);
    at(pyramid_binding).read(out.pyramid.data(), pyramid_floats * sizeof(float));
    out.counts = counts(f);
    return out;
}

GlLayerCounts GlLayerBuilder::Passes::counts(const gl::Functions& f) const {
    gl::check_gl(f, "dof-secondary: the layer passes");
    std::uint32_t words[BC_LAYER_COUNTS];
    at(counts_binding).read(words, sizeof words);
    return GlLayerCounts{words[BC_LAYER_COUNT_FRAGMENTS], words[BC_LAYER_COUNT_CULLED_NEAR],
                         words[BC_LAYER_COUNT_CULLED_IN_FRONT], words[BC_LAYER_COUNT_CULLED_NORMAL],
                         words[BC_LAYER_COUNT_DROPPED]};
}

GlLayerBuilder::GlLayerBuilder(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      passes_(std::make_unique<Passes>(Passes{
          gl::Program(context.gl(), {layer_stage(GL_COMPUTE_SHADER, "render_layers_setup.comp")}),
          gl::Program(context.gl(),
                      {layer_stage(GL_VERTEX_SHADER, "render_layers.vert"),
                       layer_stage(GL_FRAGMENT_SHADER, "render_layers.frag", gl::Prelude::layer_fragments)}),
          gl::Program(context.gl(),
                      {layer_stage(GL_COMPUTE_SHADER, "render_layers_raster.comp", gl::Prelude::layer_fragments)}),
          gl::Program(context.gl(), {layer_stage(GL_COMPUTE_SHADER, "render_layers_cluster_depth.comp")}),
          gl::Program(context.gl(), {layer_stage(GL_COMPUTE_SHADER, "render_layers_pyramid.comp")}),
          gl::VertexArray(context.gl()), {}})) {}

// The passes' glDelete* act on the current context: this one's, with several alive.
GlLayerBuilder::~GlLayerBuilder() { context_->make_current_for_release(); }

namespace {

// The pyramid's floats for a base of `size` texels per side.
std::size_t pyramid_floats_of(int size) {
    std::size_t floats = 0;
    for (int s : level_sizes(size)) floats += 2 * static_cast<std::size_t>(s) * static_cast<std::size_t>(s);
    return floats;
}

// The layers' buffers ([layer][y][x] words) must fit a storage block, and
// the GL rasterizer's viewport and target the image.
void check_layer_limits(const gl::Functions& f, int size, int layers, GlLayerRaster raster) {
    if (layers < 1 || layers > BC_LAYERS_MAX) throw gl::GlError("gl: " + std::to_string(layers) + " layers, not 1 to 8");
    const auto limit = static_cast<std::size_t>(static_cast<unsigned>(get_integer(f, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)));
    const std::size_t bytes = static_cast<std::size_t>(size) * static_cast<std::size_t>(size) *
                              static_cast<std::size_t>(layers) * sizeof(std::uint32_t);
    int raster_limit = size;
    if (raster == GlLayerRaster::graphics) {
        GLint max_viewport[2] = {0, 0};
        f.GetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
        raster_limit = std::min({get_integer(f, GL_MAX_TEXTURE_SIZE), max_viewport[0], max_viewport[1]});
    }
    if (size < 2 || size > raster_limit || bytes > limit)
        throw gl::GlError("gl: layer size " + std::to_string(size) + " with " + std::to_string(layers) +
                          " layers is below 2 texels or exceeds the context's limits (" + std::to_string(bytes >> 20) +
                          " MiB a buffer, at most " + std::to_string(limit >> 20) + ")");
}

}  // namespace

void GlLayerBuilder::make_layers(const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                                 bool with_triangles, GlLayerRaster raster) const {
    const gl::Functions& f = *gl_;
    check_layer_limits(f, view.size, layers, raster);
    passes_->upload(f, view, layers, input, pyramid_floats_of(view.size), with_triangles);
    passes_->make_fans(f, input);
    if (raster == GlLayerRaster::compute)
        passes_->raster_fans(f, input.vertices->size());
    else
        passes_->draw_fans(f, view.size);
    passes_->make_pyramid(f, view.size);
}

GlClusterLayers GlLayerBuilder::build(const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                                      GlLayerRaster raster) const {
    make_layers(view, layers, input, true, raster);
    return passes_->read_back(*gl_, view.size, layers, pyramid_floats_of(view.size));
}

void GlLayerBuilder::upload_triangles(const std::vector<std::array<glm::vec3, 3>>& vertices,
                                      const std::vector<glm::vec3>& normals) const {
    passes_->upload_triangles(*gl_, vertices, normals);
    passes_->reset_counts(*gl_);
}

void GlLayerBuilder::build_resident(const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                                    GlLayerRaster raster) const {
    make_layers(view, layers, input, false, raster);
}

GlLayerCounts GlLayerBuilder::read_counts() const { return passes_->counts(*gl_); }

const gl::Buffer& GlLayerBuilder::depth_buffer() const { return passes_->at(layer_depth_binding); }
const gl::Buffer& GlLayerBuilder::triangle_buffer() const { return passes_->at(layer_triangle_binding); }
const gl::Buffer& GlLayerBuilder::pyramid_buffer() const { return passes_->at(pyramid_binding); }

}  // namespace blurcull::frontend
