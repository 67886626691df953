// The CPU tile rasterizer's lens and time bounds of one triangle: per block
// (the kernel's tile, frame_context.hpp) and per footprint, through the
// kernel's public steps, with the cull's decisions read from its traits
// (kernel cull_traits): which blocks get bounds of their own, where the
// edge planes pay, when footprints share their axis bounds along columns
// and rows, and whether a block's planes cull a footprint whole.
#pragma once

#include "render/cpu/frame_context.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace blurcull::frontend::cpu_tiles {

template <class Real>
class FootprintBounds {
public:
    using K = blurcull::kernel<Real>;
    using Triangle = TileTriangle<K>;

    explicit FootprintBounds(const FrameContext<Real>& frame) : frame_(frame) {}

    // A triangle whose part in the tile is the pixels [rx0, rx1] x [ry0, ry1]:
    // whether its footprints share their axis bounds (current.share_axes),
    // and empty caches for them. Footprints share them where they carry no
    // planes of their own: a cull without planes, or edge planes that come
    // from the block (with_tile_planes adds them). The hyperplanes'
    // footprint test needs each footprint's own bounds.
    void begin_triangle(Triangle& current, int rx0, int ry0, int rx1, int ry1) {
        const int traits = frame_.cull_traits;
        const bool edges_in_blocks = (traits & BC_CULL_EDGE_PLANES_PER_BLOCK) != 0 && frame_.block > frame_.footprint;
        current.share_axes = current.needs_bounds && ((traits & BC_CULL_ADDS_PLANES) == 0 || edges_in_blocks) &&
                             K::sample_bounds_apply(*current.tri);
        if (current.share_axes) {
            columns_.reset(rx0, rx1, frame_.footprint);
            rows_.reset(ry0, ry1, frame_.footprint);
        }
    }

    // What to do with a block [bx0, bx1] x [by0, by1] of the triangle's part.
    enum class Block {
        skip,        // its bounds hold no sample
        whole,       // test its samples against block_bounds() as one footprint
        footprints,  // bound and test each footprint (footprint_in_block)
    };

    // The block's own bound pays only where it can spare several footprint
    // bounds (on one footprint it is the same bound); with planes it also
    // carries the planes its footprints share (the kernel's tile then
    // footprint: their setup once per block). Edge planes: a block with too
    // few samples for them to pay (even all of them visited) is culled
    // without them. Hyperplanes: always from the block.
    Block block(const Triangle& current, int bx0, int by0, int bx1, int by1) {
        const int traits = frame_.cull_traits, footprint = frame_.footprint;
        const int spanned = (bx1 / footprint - bx0 / footprint + 1) + (by1 / footprint - by0 / footprint + 1);
        const bool edges_method = (traits & BC_CULL_EDGE_PLANES_PER_BLOCK) != 0;
        const bool hyperplane = (traits & BC_CULL_HYPERPLANES_PER_TILE) != 0;
        const double block_samples = double((bx1 - bx0 + 1) * (by1 - by0 + 1)) * double(frame_.spp);
        const bool edges = (edges_method && block_samples >= frame_.edge_min_samples) || hyperplane;
        block_bounds_ = K::no_sample_bounds();
        const bool block_bounded = frame_.block > footprint && (spanned > 4 || edges);
        if (block_bounded) {
            block_bounds_ = edges_method ? edge_block_bounds(current, bx0, by0, bx1, by1)
                                         : bounds_of(current, bx0, by0, bx1, by1);
            if (block_bounds_.empty) return Block::skip;
            // Planes, the block's part of the triangle inside one footprint:
            // the block's bounds are that footprint's.
            if (edges && spanned == 2) return Block::whole;
        }
        block_planes_ = (traits & BC_CULL_ADDS_PLANES) != 0 && K::plane_pieces(block_bounds_) > 0;
        return Block::footprints;
    }
    const typename K::SampleBounds& block_bounds() const { return block_bounds_; }

    // The bounds of footprint [px0, px1] x [py0, py1] of the last block():
    // with the block's planes (from the shared axes, or the kernel's
    // sample_bounds_in_tile) where it has them.
    typename K::SampleBounds footprint_in_block(const Triangle& current, int px0, int py0, int px1, int py1) {
        if (!block_planes_) return footprint_bounds(current, px0, py0, px1, py1);
        if (!current.share_axes) return bounds_of(current, px0, py0, px1, py1, &block_bounds_);
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        return K::with_tile_planes(typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w), frame_.cull,
                                   footprint_bounds(current, px0, py0, px1, py1), block_bounds_);
    }

    // NDC box (lo.xy, hi.xy) of the pixels [px0, px1] x [py0, py1] (rows grow downwards).
    typename K::vec4 footprint(int px0, int py0, int px1, int py1) const {
        return typename K::vec4(kernelf::pixel_rect_ndc(glm::ivec4(px0, py0, px1, py1), frame_.model.image_size()));
    }

    // The NDC box of a footprint grown by a few float roundings: it holds
    // every sample position of its pixels (floats), with room to spare.
    typename K::vec4 padded_footprint(int px0, int py0, int px1, int py1) const {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const Real ulps = Real(8) * Real(std::numeric_limits<float>::epsilon());
        const Real pad_x = ulps * std::max(Real(1), std::max(std::abs(box.x), std::abs(box.z)));
        const Real pad_y = ulps * std::max(Real(1), std::max(std::abs(box.y), std::abs(box.w)));
        return typename K::vec4(box.x - pad_x, box.y - pad_y, box.z + pad_x, box.w + pad_y);
    }

    // Planes: whether every shutter piece's planes cull the whole footprint
    // (then none of its samples can pass; not visited).
    bool planes_cull_footprint(const typename K::SampleBounds& sb, int px0, int py0, int px1, int py1) const {
        const int pieces = K::plane_pieces(sb);
        if (pieces == 0) return false;
        const typename K::vec4 box = padded_footprint(px0, py0, px1, py1);
        const typename K::vec2 s_lo(box.x, box.y), s_hi(box.z, box.w);
        for (int q = 0; q < pieces; ++q)
            if (!K::plane_piece_culls_box(sb, q, s_lo, s_hi)) return false;
        return true;
    }

    // Sample bounds set up (blocks and footprints), and those that held nothing.
    std::uint64_t bounded = 0, bounded_empty = 0;

private:
    // One axis's bounds per footprint column (row) of the triangle's
    // rectangle, computed when first needed.
    struct AxisCache {
        std::vector<typename K::SampleAxisBounds> bounds;
        std::vector<char> ready;
        int origin = 0;  // first pixel of column (row) 0

        void reset(int first, int last, int footprint) {
            origin = first - first % footprint;
            ready.assign(static_cast<std::size_t>((last - origin) / footprint + 1), 0);
            bounds.resize(ready.size());
        }
        template <class Compute>
        const typename K::SampleAxisBounds& get(int pixel, int footprint, Compute compute) {
            const std::size_t i = static_cast<std::size_t>((pixel - origin) / footprint);
            if (!ready[i]) {
                bounds[i] = compute();
                ready[i] = 1;
            }
            return bounds[i];
        }
    };

    // The sample bounds of a block or footprint, counted; a footprint's from
    // its block's bounds `tile` when given (kernel::sample_bounds_in_tile).
    typename K::SampleBounds bounds_of(const Triangle& current, int px0, int py0, int px1, int py1,
                                       const typename K::SampleBounds* tile = nullptr) {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const typename K::vec2 lo(box.x, box.y), hi(box.z, box.w);
        typename K::SampleBounds sb = tile ? K::sample_bounds_in_tile(*current.tri, lo, hi, frame_.cull, *tile)
                                           : K::sample_bounds(*current.tri, lo, hi, frame_.cull);
        ++bounded;
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    // Edge-plane bounds of a block (BC_CULL_EDGE_PLANES_PER_BLOCK): its
    // bounds without planes, and the planes only where the samples it leaves
    // to visit (its pixels' samples in its shutter interval) are enough to
    // repay their setup; elsewhere the block's footprints are culled without
    // them (fewer culls, never a wrong one).
    typename K::SampleBounds edge_block_bounds(const Triangle& current, int px0, int py0, int px1, int py1) {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const typename K::vec2 lo(box.x, box.y), hi(box.z, box.w);
        typename K::SampleBounds sb = K::sample_bounds_without_planes(*current.tri, lo, hi, frame_.cull);
        ++bounded;
        if (!sb.empty) {
            const typename K::vec2 range = K::sample_time_range(sb);
            const double share = std::clamp(double(range.y) - double(range.x), 0.0, 1.0);
            const double visits = double((px1 - px0 + 1) * (py1 - py0 + 1)) * double(frame_.spp) * share;
            if (visits >= frame_.edge_min_samples) sb = K::add_sample_planes(*current.tri, lo, hi, frame_.cull, sb);
        }
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    // The sample bounds of a footprint, counted: with share_axes from its
    // column's and its row's axis bounds (the kernel's sample_bounds split
    // in two: the same bounds, each axis computed once per column or row).
    typename K::SampleBounds footprint_bounds(const Triangle& current, int px0, int py0, int px1, int py1) {
        if (!current.share_axes) return bounds_of(current, px0, py0, px1, py1);
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const int fp = frame_.footprint, cull = frame_.cull;
        const typename K::MovingTriangle& tri = *current.tri;
        ++bounded;
        const auto& x = columns_.get(px0, fp, [&] { return K::sample_axis_bounds(tri, 0, box.x, box.z, cull); });
        typename K::SampleBounds sb = K::no_sample_bounds();
        sb.empty = true;
        if (!x.empty) {
            const auto& y = rows_.get(py0, fp, [&] { return K::sample_axis_bounds(tri, 1, box.y, box.w, cull); });
            sb = K::combine_axis_bounds(x, y);
        }
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    const FrameContext<Real>& frame_;
    AxisCache columns_, rows_;  // the current triangle's axis bounds (share_axes)
    typename K::SampleBounds block_bounds_{};  // the last block's (block())
    bool block_planes_ = false;                // they carry planes for its footprints
};

}  // namespace blurcull::frontend::cpu_tiles
