#!/usr/bin/env python3
"""Plots bench_cpu_embree's CSV (--csv): process CPU time per renderer against
samples per pixel (`spp`) or against the image's pixels (`size`), one panel
per scene, log-log, Embree included (docs/benchmarks.md, "Time against spp
and resolution").

    build/bench/bench_cpu_embree --scenes forest,hand --size 512x384 --spp 4,16,64 \\
        --blur 1 --repeat 1 --culls bbox,twostage --csv docs/cpu_embree_spp.csv
    /usr/bin/python3 bench/cpu/plot_cpu_embree.py spp docs/cpu_embree_spp.csv docs/images/cpu-embree-spp.png

Needs Debian's python3-matplotlib.
"""
import csv
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

STYLE = {
    "embree": dict(color="#000000", marker="*", linestyle="-", linewidth=2),
    "cpu bbox": dict(color="#999999", marker="o", linestyle=":"),
    "cpu hull": dict(color="#7fa8e6", marker="v", linestyle="--"),
    "cpu dualspace": dict(color="#2f9e44", marker="^", linestyle="-"),
    "cpu twostage": dict(color="#1f5fbf", marker="s", linestyle="-"),
    "cpu edges": dict(color="#d0452f", marker="D", linestyle="-"),
}


def x_value(row, axis):
    if axis == "spp":
        return int(row["spp"])
    return int(row["width"]) * int(row["height"])


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("spp", "size"):
        sys.exit("usage: plot_cpu_embree.py spp|size RESULTS.csv OUT.png")
    axis, source, output = sys.argv[1:]
    series = OrderedDict()  # scene -> renderer -> [(x, cpu s)]
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            scene = "%s, blur %s" % (row["scene"], row["blur"])
            series.setdefault(scene, defaultdict(list))[row["renderer"]].append(
                (x_value(row, axis), float(row["cpu_s"])))
    if not series:
        sys.exit("plot_cpu_embree.py: no rows in " + source)
    fig, axes = plt.subplots(1, len(series), figsize=(4.2 * len(series), 3.6), squeeze=False)
    for panel, (scene, renderers) in zip(axes[0], series.items()):
        for renderer, points in renderers.items():
            points.sort()
            panel.plot([p[0] for p in points], [p[1] for p in points], label=renderer,
                       **STYLE.get(renderer, {}))
        panel.set_xscale("log", base=2 if axis == "spp" else 10)
        panel.set_yscale("log")
        panel.set_title(scene)
        panel.set_xlabel("samples per pixel" if axis == "spp" else "pixels")
        panel.set_ylabel("process CPU time (s)")
        panel.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=110)


if __name__ == "__main__":
    main()
