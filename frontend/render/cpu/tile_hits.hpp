// A work tile's hits for the CPU tile rasterizer: the exact test of the
// samples the culls and the fast test kept (covers4 four at a time in
// double), the alpha mask, the depth rule (nearest, then lowest index), the
// occlusion test's farthest depths, and the resolve of the samples into the
// image (box filter, progressive sums, sample ids).
#pragma once

#include "render/common/image.hpp"
#include "render/common/method_plan.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "render/cpu/exact_lanes.hpp"
#include "render/cpu/farthest_depths.hpp"
#include "render/cpu/frame_context.hpp"
#include "render/cpu/tile_samples.hpp"

#include <blurcull/kernel.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace blurcull::frontend::cpu_tiles {

template <class Real>
class TileHits {
public:
    using K = blurcull::kernel<Real>;
    using Triangle = TileTriangle<K>;

    TileHits(const FrameContext<Real>& frame, const TileSamples<Real>& samples)
        : frame_(frame), samples_(samples), depth_(samples.capacity()), hit_(samples.capacity()) {}

    // Empty depths and hits for the loaded tile's samples.
    void clear() {
        const std::size_t count = samples_.pixels() * frame_.spp;
        for (std::size_t k = 0; k < count; ++k) {
            depth_[k] = std::numeric_limits<Real>::infinity();
            hit_[k] = none;
        }
    }

    // The samples were just grouped by stratum: every farthest depth is due
    // (triangles may have drawn before the grouping).
    void track_strata() {
        farthest_.reset(frame_.setup.strata.count(), samples_.width(), samples_.y1() - samples_.y0() + 1,
                        samples_.strata_starts(), samples_.strata_slots(), depth_.data());
    }
    FarthestDepths<Real>& farthest() { return farthest_; }

    // The exact test of a sample the fast test kept (sample_test's last
    // step), and the depth rule. In double the samples wait in `pending_`
    // and go through covers four at a time (covers4: covers' verdicts and
    // depths bit for bit); flush_exact at the end of each triangle keeps the
    // triangle order of the depth rule.
    void test_exactly(const Triangle& current, std::size_t k) {
        if constexpr (std::is_same_v<Real, double>) {
            pending_[pending_count_++] = k;
            if (pending_count_ == pending_.size()) flush_exact(current);
        } else {
            const SampleLanes& lanes = samples_.lanes();
            const typename K::vec2 ndc(lanes.sx()[k], lanes.sy()[k]), lens(lanes.u()[k], lanes.v()[k]);
            Real z = Real(0);
            if (K::covers(*current.tri, ndc, lens, static_cast<Real>(lanes.t()[k]), frame_.near, z))
                record_hit(current, k, z);
        }
    }

    // covers4 on the pending samples (the last one repeated into unused lanes).
    void flush_exact(const Triangle& current) {
        if constexpr (std::is_same_v<Real, double>) {
            if (pending_count_ == 0) return;
            const SampleLanes& lanes = samples_.lanes();
            double sx[4], sy[4], u[4], v[4], t[4], z[4];
            for (std::size_t i = 0; i < 4; ++i) {
                const std::size_t k = pending_[std::min(i, pending_count_ - 1)];
                sx[i] = lanes.sx()[k];
                sy[i] = lanes.sy()[k];
                u[i] = lanes.u()[k];
                v[i] = lanes.v()[k];
                t[i] = lanes.t()[k];
            }
            const std::uint32_t covered = covers4(*current.tri, sx, sy, u, v, t, frame_.near, z);
            for (std::size_t i = 0; i < pending_count_; ++i)
                if ((covered >> i) & 1u) record_hit(current, pending_[i], z[i]);
            pending_count_ = 0;
        } else {
            (void)current;
        }
    }

    // The box filter of the tile's samples into its pixels; a progressive
    // pass continues its pixel's sums from the passes before.
    void resolve(Image& image) const {
        const int summed = static_cast<int>(frame_.first_sample + frame_.spp);
        for (int py = samples_.y0(); py <= samples_.y1(); ++py) {
            for (int px = samples_.x0(); px <= samples_.x1(); ++px) {
                const std::size_t at = image.index(px, py);
                glm::vec3 sum = frame_.sums != nullptr ? frame_.sums->colour[at] : glm::vec3(0.0f);
                std::uint32_t covered = frame_.sums != nullptr ? frame_.sums->covered[at] : 0;
                for (std::uint32_t j = 0; j < frame_.spp; ++j) {
                    const std::size_t k = samples_.slot(px, py, j);
                    sum += frame_.shader.sample_colour(hit_[k], samples_.ndc_of(k), samples_.lens_of(k),
                                                       samples_.shutter_time(k));
                    covered += hit_[k] != none;
                    if (frame_.sample_ids != nullptr) {
                        const std::size_t pixel = static_cast<std::size_t>(py) * frame_.settings.width + px;
                        (*frame_.sample_ids)[pixel * frame_.spp + j] = hit_[k] == none ? no_sample_hit : hit_[k];
                    }
                }
                if (frame_.sums != nullptr) {
                    frame_.sums->colour[at] = sum;
                    frame_.sums->covered[at] = covered;
                }
                image.at(px, py) = resolve_box(sum, summed);
                image.coverage[at] = resolve_coverage(covered, summed);
            }
        }
    }

    // Covered samples found (the alpha mask's kept ones, whether they won or not).
    std::uint64_t hits = 0;

private:
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

    // A covered sample at depth z: the alpha mask, the count, the depth rule.
    void record_hit(const Triangle& current, std::size_t k, Real z) {
        // The scene triangle wins, lowest index on equal depths also across
        // the motion-segment groups (within one group the order does it).
        const std::uint32_t source = frame_.setup.pieces[current.index].source;
        // alphaMode MASK: a masked-out sample is not covered (before the
        // depth test); the shader takes the sample's shutter time.
        if (frame_.shader.masked(source) &&
            !frame_.shader.sample_kept(source, samples_.ndc_of(k), samples_.lens_of(k), samples_.shutter_time(k)))
            return;
        ++hits;
        if (K::depth_nearer(z, depth_[k]) || (z == depth_[k] && source < hit_[k])) {
            depth_[k] = z;
            hit_[k] = source;
            if (samples_.strata_grouped()) {
                const std::size_t pixel = k / frame_.spp;
                const std::size_t width = static_cast<std::size_t>(samples_.width());
                farthest_.changed(samples_.stratum(k), pixel % width, pixel / width);
            }
        }
    }

    const FrameContext<Real>& frame_;
    const TileSamples<Real>& samples_;
    std::vector<Real> depth_;
    std::vector<std::uint32_t> hit_;
    FarthestDepths<Real> farthest_;         // the occlusion test's depths (track_strata)
    std::array<std::size_t, 4> pending_{};  // samples waiting for covers4 (double only)
    std::size_t pending_count_ = 0;
};

}  // namespace blurcull::frontend::cpu_tiles
