// The GL build of dof-secondary's layered images and min/max depth pyramid
// (docs/secondary-rays.md, "What the gl backend runs"): per cluster, a
// compute pass clips and projects the scene's triangles into the virtual
// view, the GL rasterizer or a compute scan (GlLayerRaster) takes them twice
// into a k-buffer (per texel the `layers` nearest depths by an atomicMin
// cascade, then their triangles), and a compute pass per level builds the
// pyramid. The paper's three culls
// are applied on the GPU: near plane by clipping, the cluster's own triangles
// and the depths not beyond its nearest ray origin in the texel, and the
// normal cone. Same arithmetic as the host's build (layer_raster_shared.h);
// render/secondary's types are filled from the result in app/gl_dof_secondary.hpp.
#pragma once

#include "render/gl/gl_context.hpp"

#include <blurcull/kernel.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace blurcull::frontend {

// What the passes counted (render/secondary's LayerStats).
struct GlLayerCounts {
    std::uint64_t fragments = 0, culled_near = 0, culled_in_front = 0, culled_normal = 0, dropped = 0;
};

// One cluster's layers as read back.
struct GlClusterLayers {
    int size = 0;
    int layers = 0;
    std::vector<float> depth;             // [layer][y][x] view depth, +infinity for none, sorted per texel
    std::vector<std::uint32_t> triangle;  // the scene triangle of each depth (0 where none)
    std::vector<float> pyramid;           // levels from size^2 down to 1^2, each cell's (lo, hi)
    GlLayerCounts counts;
};

// The scene's triangles (world space, at the middle of the rays' shutter
// slice) and a cluster's culls.
struct GlLayerInput {
    const std::vector<std::array<glm::vec3, 3>>* vertices = nullptr;
    const std::vector<glm::vec3>* normals = nullptr;  // unit winding normals
    const std::vector<std::uint8_t>* own = nullptr;   // per triangle: the cluster's own
    const std::vector<glm::vec3>* origins = nullptr;  // the cluster's ray origins (none: no in-front cull)
    float normal_threshold = 2.0f;                    // cull n . forward above this
    // Instead of `origins`, where origin_points is set: origin_count
    // origins on the GPU, origin i the first vec4 of point origin_indices[i]
    // of origin_points (GlClustering's buffer, 2 vec4 a ray).
    const gl::Buffer* origin_points = nullptr;
    const gl::Buffer* origin_indices = nullptr;
    std::size_t origin_count = 0;
    // Instead of `own` and normal_threshold, where own_source is set: the
    // own bits ((triangles + 31) / 32 words from byte own_offset) and the
    // threshold (a float at byte threshold_offset of threshold_source)
    // copied on the GPU (GlClustering::group's), nothing read back.
    const gl::Buffer* own_source = nullptr;
    std::size_t own_offset = 0;
    const gl::Buffer* threshold_source = nullptr;
    std::size_t threshold_offset = 0;
};

// What finds the texel centres each projected triangle covers. compute: a
// work group per triangle runs the host scan's coverage test
// (layer_raster_shared.h), so the same texels as the host on any GPU, on
// every multiprocessor (an H200 runs its graphics stages on 4 of 132);
// graphics: the GL rasterizer (llvmpipe's is many times faster than its
// compute; a GPU's snaps to its own fixed point, so an edge texel may
// differ from the host's). The same layers on an IEEE-exact GL.
enum class GlLayerRaster { graphics, compute };

class GlLayerBuilder {
public:
    // On `context` (kept alive by the caller; made current here, and by its
    // destructor to delete its objects); compiles the passes. build() runs
    // on the current context: the caller makes `context` current first.
    // Throws gl::GlError with the compiler's log.
    explicit GlLayerBuilder(const gl::HeadlessContext& context);
    ~GlLayerBuilder();
    GlLayerBuilder(const GlLayerBuilder&) = delete;
    GlLayerBuilder& operator=(const GlLayerBuilder&) = delete;

    // The layered image of `view` (view.size^2 texels, 1 <= layers <= 8)
    // with the culls of `input`, and its pyramid. Throws gl::GlError when GL
    // reports an error or the image exceeds the context's limits.
    GlClusterLayers build(const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                          GlLayerRaster raster = GlLayerRaster::graphics) const;

    // The GPU-resident build (GlClusterBouncer): the scene's triangles
    // uploaded once per render, then per cluster build_resident, which is
    // build() with input.vertices and input.normals taken from the last
    // upload_triangles (only their count is read from input.vertices) and
    // nothing read back, so the host does not wait for it: the layers'
    // depths, triangles (~0 for none) and pyramid stay in the buffers below
    // until the next build, and read_counts gives the counts summed over the
    // builds since upload_triangles (call it after the passes that use the
    // layers: it waits for them). Same throws as build().
    void upload_triangles(const std::vector<std::array<glm::vec3, 3>>& vertices,
                          const std::vector<glm::vec3>& normals) const;
    void build_resident(const kernelf::LayerView& view, int layers, const GlLayerInput& input,
                        GlLayerRaster raster = GlLayerRaster::graphics) const;
    GlLayerCounts read_counts() const;
    const gl::Buffer& depth_buffer() const;     // [layer][y][x] float bits, +infinity for none
    const gl::Buffer& triangle_buffer() const;  // [layer][y][x] scene triangle, ~0 for none
    const gl::Buffer& pyramid_buffer() const;   // GlClusterLayers::pyramid's layout

    struct Passes;

private:
    // The passes up to the pyramid (build's and build_resident's).
    void make_layers(const kernelf::LayerView& view, int layers, const GlLayerInput& input, bool with_triangles,
                     GlLayerRaster raster) const;

    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<Passes> passes_;
};

}  // namespace blurcull::frontend
