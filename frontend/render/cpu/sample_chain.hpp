// The culling half of the per-sample chain (kernel::sample_culled) on many
// samples at once, for the CPU backend's inner loop: a mask of the samples
// that pass, branch-free, four double lanes at a time with AVX where the CPU
// has it. Same operations in the same order as the kernel (a product, then a
// sum, never fused), so every decision is the kernel's.
#pragma once

#include <blurcull/kernel.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// Samples as arrays of coordinates (structure of arrays): double for the
// chain, float for the fast coverage test (both exact: the samples are
// floats). Padded by 32 so that a batch may read past the last sample.
class SampleLanes {
public:
    explicit SampleLanes(std::size_t size);
    // Inline: the tiles set every sample once and copy it once more.
    void set(std::size_t k, float sx, float sy, float u, float v, float t) {
        dsx_[k] = sx;
        dsy_[k] = sy;
        du_[k] = u;
        dv_[k] = v;
        dt_[k] = t;
        fsx_[k] = sx;
        fsy_[k] = sy;
        fu_[k] = u;
        fv_[k] = v;
        ft_[k] = t;
        // & rather than &&: no branch per sample.
        in_unit_range_ = in_unit_range_ & (u >= -1.0f) & (u <= 1.0f) & (v >= -1.0f) & (v <= 1.0f) & (t >= 0.0f) &
                         (t <= 1.0f);
    }
    // Sets sample k's time (a motion segment's local time).
    void set_time(std::size_t k, float t) {
        dt_[k] = t;
        ft_[k] = t;
        in_unit_range_ = in_unit_range_ & (t >= 0.0f) & (t <= 1.0f);
    }
    // Copies sample `from` of `other` into slot k.
    void copy(std::size_t k, const SampleLanes& other, std::size_t from) {
        set(k, other.fsx_[from], other.fsy_[from], other.fu_[from], other.fv_[from], other.ft_[from]);
    }
    const double* sx() const { return dsx_.data(); }
    const double* sy() const { return dsy_.data(); }
    const double* u() const { return du_.data(); }
    const double* v() const { return dv_.data(); }
    const double* t() const { return dt_.data(); }
    const float* fsx() const { return fsx_.data(); }
    const float* fsy() const { return fsy_.data(); }
    const float* fu() const { return fu_.data(); }
    const float* fv() const { return fv_.data(); }
    const float* ft() const { return ft_.data(); }
    // Whether every sample set so far has its lens in [-1, 1]^2 and its time
    // in [0, 1] (every pattern's samples do): no_sample_bounds() passes them all.
    bool in_unit_range() const { return in_unit_range_; }

private:
    std::vector<double> dsx_, dsy_, du_, dv_, dt_;
    std::vector<float> fsx_, fsy_, fu_, fv_, ft_;
    bool in_unit_range_ = true;
};

// Bit i (i < count <= 32) set when sample first + i of `lanes` is NOT culled
// by kernel<Real>::sample_culled(screen, check_screen, bounds, ...): the
// kernel's own decision (the four-lane path runs for Real = double with AVX, edge
// planes included; the rest call the kernel one sample at a time).
template <class Real>
std::uint32_t samples_passing(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                              const typename kernel<Real>::SampleBounds& bounds, const SampleLanes& lanes,
                              std::size_t first, int count);

// samples_passing with bounds = kernel<Real>::no_sample_bounds() (no lens or
// time to cull: bbox, hull, static in-focus triangles), without comparing
// the bounds with it per call: the same mask.
template <class Real>
std::uint32_t samples_passing_screen(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                                     const SampleLanes& lanes, std::size_t first, int count);

// samples_passing one sample at a time through the kernel whatever the CPU
// (the reference the four-lane path is tested against).
template <class Real>
std::uint32_t samples_passing_scalar(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                                     const typename kernel<Real>::SampleBounds& bounds, const SampleLanes& lanes,
                                     std::size_t first, int count);

}  // namespace blurcull::frontend
