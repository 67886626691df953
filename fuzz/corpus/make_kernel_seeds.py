#!/usr/bin/env python3
"""Writes the kernel fuzzer's seed inputs (fuzz/corpus/kernel/): a few moving,
defocused triangles in the layout fuzz_kernel.cpp reads (36 floats of
positions and CoCs, near, footprint lo/hi, then samples of 5 floats).
Run from fuzz/corpus/:  python3 make_kernel_seeds.py"""
import struct


def seed(name, positions, cocs, near, lo, hi, samples):
    values = [c for p in positions for c in p] + [c for c in cocs for c in c] + [near] + list(lo) + list(hi)
    for s in samples:
        values += list(s)
    with open("kernel/" + name, "wb") as out:
        out.write(struct.pack("<%df" % len(values), *values))


SAMPLES = [(0.5, 0.5, 0.5, 0.5, 0.5), (0.0, 0.0, 0.0, 0.0, 0.0), (0.999, 0.25, 0.75, 0.5, 0.999),
           (0.3, 0.7, 0.1, 0.9, 0.4)]
tri = [(0.0, 0.0, 2.0), (1.0, 0.0, 2.0), (0.0, 1.0, 2.0)]
moved = [(x + 0.2, y, w) for x, y, w in tri]
# motion only, whole screen
seed("motion", tri + moved, [(0.0, 0.0)] * 6, 0.1, (-1.0, -1.0), (1.0, 1.0), SAMPLES)
# defocus only, one pixel
seed("defocus", tri + tri, [(0.05, 0.05)] * 6, 0.1, (0.1, 0.1), (0.102, 0.102), SAMPLES)
# both, straddling the focal plane, a vertex behind the eye at close
both = [(0.0, 0.0, 2.0), (1.0, 0.0, 1.0), (0.0, 1.0, 3.0), (0.1, 0.0, 2.0), (1.0, 0.2, -0.5), (0.0, 1.0, 3.5)]
seed("both_near", both, [(0.02, 0.02), (-0.02, -0.02), (0.04, 0.04), (0.02, 0.02), (-0.06, -0.06), (0.05, 0.05)],
     0.05, (0.0, 0.0), (0.03, 0.03), SAMPLES)
