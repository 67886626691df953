#!/usr/bin/env python3
"""Summarises `blurcull view --backend cpu --frames N` (its stdout, on stdin):
per cull method the median wall and CPU time of the previews (each view's
first image, with its scale) and of the full-size 1-spp passes, the frames
per second they give, and each view's time to reach the target spp.

  xvfb-run -a ./build/frontend/blurcull view --backend cpu --frames 12 --spp 16 \
      | python3 bench/view/view_passes.py
"""
import re
import statistics
import sys
from collections import defaultdict

LINE = re.compile(r"frame (\d+) pass (\d+): cull (\w+), (\d+)/(\d+) spp(?: \(preview 1/(\d+), \w+\))?, "
                  r"STE [0-9.]+, ([0-9.]+) ms, ([0-9.]+) ms CPU")


def main():
    previews = defaultdict(list)      # (cull, scale) -> [(wall, cpu)]
    full_one_spp = defaultdict(list)  # cull -> [(wall, cpu)]
    converge = defaultdict(float)     # frame -> wall ms to the target
    passes = defaultdict(int)
    culls = {}
    for line in sys.stdin:
        m = LINE.match(line)
        if not m:
            continue
        frame, number, cull = int(m[1]), int(m[2]), m[3]
        samples, scale = int(m[4]), int(m[6] or 1)
        wall, cpu = float(m[7]), float(m[8])
        culls[frame] = cull
        converge[frame] += wall
        passes[frame] += 1
        if number == 1:
            previews[(cull, scale)].append((wall, cpu))
        if scale == 1 and samples == 1:
            full_one_spp[cull].append((wall, cpu))

    def row(name, times):
        wall = statistics.median(t[0] for t in times)
        cpu = statistics.median(t[1] for t in times)
        print(f"| {name} | {len(times)} | {wall:.0f} | {1000 / wall:.1f} | {cpu:.0f} | {2000 / cpu:.1f} |")

    print("| image | n | wall ms (median) | frames/s (wall) | CPU ms (median) | frames/s if the 2 cores were free |")
    print("|---|---|---|---|---|---|")
    by_scale = defaultdict(list)
    for (cull, scale), times in previews.items():
        by_scale[(cull if scale == 1 else "", scale)] += times
    for (cull, scale), times in sorted(by_scale.items()):
        row(f"preview, 1/{scale} size" + (f" (accumulation's first pass, cull {cull})" if scale == 1 else ""), times)
    for cull, times in sorted(full_one_spp.items()):
        row(f"1 spp full size, cull {cull}", times)
    print()
    print("| view | cull | passes | wall s to the target spp |")
    print("|---|---|---|---|")
    for frame in sorted(converge):
        print(f"| {frame} | {culls[frame]} | {passes[frame]} | {converge[frame] / 1000:.2f} |")


if __name__ == "__main__":
    main()
