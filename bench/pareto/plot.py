#!/usr/bin/env python3
"""Plots bench_pareto's CSV: one figure per scene, error against time (log-log),
RMSE on the left and the blurred (structured) error on the right, each method
a line through its sample counts, the Pareto front of each panel drawn as a
grey staircase through ringed points, the reference's own noise dotted.

    /usr/bin/python3 bench/pareto/plot.py docs/pareto.csv docs/images

writes docs/images/pareto-<scene>.png. Needs Debian's python3-matplotlib.
"""
import csv
import sys
from collections import OrderedDict

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

STYLE = OrderedDict(
    [
        ("stochastic-clip2", dict(color="#1f5fbf", marker="o", linestyle="-", label="stochastic, clip2 cull")),
        ("stochastic-bbox", dict(color="#7fa8e6", marker="o", linestyle="--", label="stochastic, bbox cull",
                                 markerfacecolor="white")),
        ("interleave", dict(color="#d0452f", marker="s", linestyle="-", label="interleave (N = spp)")),
        ("interval", dict(color="#2f9e44", marker="^", linestyle="-", label="interval")),
        ("accum", dict(color="#8a4fbf", marker="D", linestyle="-", label="accum")),
    ]
)


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot.py: error: no rows in '{path}'")
    for r in rows:
        for key in ("ms", "rmse", "structured_error", "reference_rmse", "reference_structured"):
            r[key] = float(r[key])
        r["spp"] = int(r["spp"])
    return rows


def pareto_front(rows, key):
    """Rows no other row beats in both time and error, by increasing time."""
    front = [
        r
        for r in rows
        if not any(
            o["ms"] <= r["ms"] and o[key] <= r[key] and (o["ms"] < r["ms"] or o[key] < r[key]) for o in rows
        )
    ]
    return sorted(front, key=lambda r: r["ms"])


def panel(ax, rows, key, floor_key, title):
    for method, style in STYLE.items():
        points = sorted((r for r in rows if r["method"] == method), key=lambda r: r["spp"])
        if not points:
            continue
        ax.plot([r["ms"] for r in points], [r[key] for r in points], markersize=6, linewidth=1.4, **style)
        for r in points:
            ax.annotate(str(r["spp"]), (r["ms"], r[key]), textcoords="offset points", xytext=(4, 3),
                        fontsize=7, color=style["color"])
    front = pareto_front(rows, key)
    # Staircase: below and left of it nothing was measured.
    xs, ys = [], []
    for r in front:
        if xs:
            xs.append(r["ms"])
            ys.append(ys[-1])
        xs.append(r["ms"])
        ys.append(r[key])
    ax.plot(xs, ys, color="0.35", linewidth=4, alpha=0.25, zorder=0, solid_capstyle="round",
            label="Pareto front")
    ax.scatter([r["ms"] for r in front], [r[key] for r in front], s=150, facecolors="none",
               edgecolors="black", linewidths=1.0, zorder=3)
    floor = rows[0][floor_key]
    ax.axhline(floor, color="0.5", linestyle=":", linewidth=1, label="reference's own noise")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain = matplotlib.ticker.FuncFormatter(lambda value, _: f"{value:g}")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("wall time per frame (ms, one thread)")
    ax.set_ylabel(title)
    ax.grid(True, which="both", color="0.9", linewidth=0.6)
    ax.set_axisbelow(True)


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: plot.py <pareto.csv> <output directory>")
    rows = read_rows(argv[1])
    scenes = list(OrderedDict.fromkeys(r["scene"] for r in rows))
    for scene in scenes:
        scene_rows = [r for r in rows if r["scene"] == scene]
        first = scene_rows[0]
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
        panel(left, scene_rows, "rmse", "reference_rmse", "RMSE (linear RGB)")
        panel(right, scene_rows, "structured_error", "reference_structured",
              f"blurred-difference RMSE (Gaussian sigma {first['blur_sigma']} px)")
        left.set_title("per-pixel error (RMSE)", fontsize=10)
        right.set_title("structured error: ghosts, strobing, banding", fontsize=10)
        # Nothing is both fast and exact: the lower left corner stays empty.
        left.legend(loc="lower left", fontsize=8, framealpha=0.9)
        fig.suptitle(f"{scene}, {first['width']}x{first['height']}: error against time "
                     f"(labels: samples per pixel / N / K; ringed: Pareto front)", fontsize=11)
        out = f"{argv[2]}/pareto-{scene}.png"
        fig.savefig(out, dpi=90)
        plt.close(fig)
        print(out)


if __name__ == "__main__":
    main(sys.argv)
