// Strata of shutter and lens for the CPU backend's bbox and hull paths: the
// shutter in `time` equal slices, u and v each in `lens` equal parts, so a
// sample (u, v, t) falls in one of time * lens^2 strata, each a box of
// (u, v, t) that kernel::stratum_screen_box bounds on the screen
// (CpuOptions::time_strata, lens_strata; docs/cpu-renderer.md, "Strata").
#pragma once

#include <glm/vec2.hpp>

namespace blurcull::frontend {

struct SampleStrata {
    int time = 1;  // slices of the shutter, a power of two (exact ends)
    int lens = 1;  // parts of u and of v each, a power of two

    int count() const { return time * lens * lens; }

    // The stratum of a sample: time slice, then part of u, then of v. A
    // sample on a boundary goes to the part above, whose range holds its lower end.
    int of(float u, float v, float t) const {
        return (time_part(t) * lens + part(u, -1.0, 2.0, lens)) * lens + part(v, -1.0, 2.0, lens);
    }

    // Stratum s's closed ranges of time, u and v (of's parts).
    template <class Real>
    void ranges(int s, glm::vec<2, Real>& t_range, glm::vec<2, Real>& u_range, glm::vec<2, Real>& v_range) const {
        t_range = range<Real>(0.0, 1.0, s / (lens * lens), time);
        u_range = range<Real>(-1.0, 2.0, (s / lens) % lens, lens);
        v_range = range<Real>(-1.0, 2.0, s % lens, lens);
    }

private:
    // part(t, 0, 1, time): t * time is exact in float (time a power of two),
    // so its integer part is the slice, a boundary k / time going to slice k.
    int time_part(float t) const {
        const float scaled = t * float(time);
        const int k = scaled > 0.0f ? static_cast<int>(scaled) : 0;
        return k < time ? k : time - 1;
    }
    // Which of `parts` equal parts of [lo, lo + size] holds x: a first guess
    // by scaling (a multiplication: parts and size are powers of two), then
    // settled by comparison with the parts' ends (exact in double for parts
    // a power of two), so rounding cannot misplace it.
    static int part(float x, double lo, double size, int parts) {
        if (parts == 1) return 0;
        const double step = size / double(parts);
        const double scaled = (double(x) - lo) * (double(parts) / size);
        int k = scaled >= double(parts) ? parts - 1 : (scaled > 0.0 ? static_cast<int>(scaled) : 0);
        while (k > 0 && double(x) < lo + step * double(k)) --k;
        while (k + 1 < parts && double(x) >= lo + step * double(k + 1)) ++k;
        return k;
    }
    template <class Real>
    static glm::vec<2, Real> range(double lo, double size, int k, int parts) {
        return glm::vec<2, Real>(static_cast<Real>(lo + size * double(k) / double(parts)),
                                 static_cast<Real>(lo + size * double(k + 1) / double(parts)));
    }
};

}  // namespace blurcull::frontend
