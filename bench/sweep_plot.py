#!/usr/bin/env python3
"""Plots the blur sweeps of docs/benchmarks.md ("Sweeps"): STE and time per
culling method against the blur.

    /usr/bin/python3 bench/sweep_plot.py triangle docs/sweep_triangle.csv docs/images/sweep-triangle.png
    /usr/bin/python3 bench/sweep_plot.py scenes docs/sweep_scenes.csv docs/images/sweep-scenes.png

`triangle` reads bench_sweep's CSV (one panel pair per sweep: motion, defocus,
both; x = blur in pixels), `scenes` bench_scenes' CSV (one panel pair per
scene; x = blur scale). Top row STE, bottom row time (ns per pixel, or the
render time as a ratio to bbox's). Needs Debian's python3-matplotlib.
"""
import csv
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

STYLE = OrderedDict(
    [
        ("bbox", dict(color="#999999", marker="o", linestyle=":")),
        ("hull", dict(color="#7fa8e6", marker="v", linestyle="--")),
        ("dualspace", dict(color="#2f9e44", marker="^", linestyle="-")),
        ("clip2", dict(color="#1f5fbf", marker="s", linestyle="-")),
        ("twostage", dict(color="#1f5fbf", marker="s", linestyle="-")),
        ("edges", dict(color="#d0452f", marker="D", linestyle="-", linewidth=2)),
    ]
)


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def series(rows, group_key, x_key, y_key, x_scale=float):
    """{group: {method: [(x, y), ...]}} sorted by x."""
    out = defaultdict(lambda: defaultdict(list))
    for r in rows:
        out[r[group_key]][r["method"]].append((x_scale(r[x_key]), float(r[y_key])))
    for group in out.values():
        for points in group.values():
            points.sort()
    return out


def plot(kind, csv_path, png_path):
    rows = read(csv_path)
    if kind == "triangle":
        ste = series(rows, "sweep", "blur_px", "ste")
        time = series(rows, "sweep", "blur_px", "ns_per_pixel")
        groups = [g for g in ("motion", "defocus", "both") if g in ste]
        x_label, time_label = "blur (pixels)", "ns per pixel (1 thread)"
    else:
        ste = series(rows, "scene", "blur", "ste")
        # CPU time where the CSV has it (bench_scenes since issue 12), else wall time.
        cpu = "cpu_ratio_to_bbox" in rows[0]
        time = series(rows, "scene", "blur", "cpu_ratio_to_bbox" if cpu else "time_ratio_to_bbox")
        groups = list(ste.keys())
        x_label = "blur scale (x the scene's own)"
        time_label = "CPU time / bbox's" if cpu else "render time / bbox's"
    fig, axes = plt.subplots(2, len(groups), figsize=(4.2 * len(groups), 7), squeeze=False)
    for col, group in enumerate(groups):
        for row, (data, label) in enumerate(((ste, "STE"), (time, time_label))):
            ax = axes[row][col]
            for method, points in data[group].items():
                style = STYLE.get(method, {})
                xs = [max(x, 0.5 if kind == "triangle" else x) for x, _ in points]
                ys = [100 * y if row == 0 else y for _, y in points]
                ax.plot(xs, ys, label=method, **style)
            ax.set_xscale("log", base=2)
            if kind == "triangle":
                ax.set_xticks([0.5, 1, 2, 4, 8, 16, 32, 64])
                ax.set_xticklabels(["0", "1", "2", "4", "8", "16", "32", "64"])
            if row == 0:
                ax.set_title(group)
                ax.set_ylabel("STE (%)")
                ax.set_ylim(0, 100)
            else:
                ax.set_ylabel(label)
                ax.set_ylim(bottom=0)
                ax.set_xlabel(x_label)
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=90)


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("triangle", "scenes"):
        sys.exit("usage: sweep_plot.py triangle|scenes input.csv output.png")
    plot(sys.argv[1], sys.argv[2], sys.argv[3])
