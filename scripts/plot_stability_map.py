#!/usr/bin/env python3
"""Stability map of a `sealfe stability` run with a Second parameter: the stable and unstable
regions of the swept speed against the second parameter, with the threshold curves.

usage: plot_stability_map.py stability_map.csv stability_sweep.csv stability_map.png
                             [parameter_value swept_speed [swept_ring]]

stability_map.csv holds the verdict on the grid (parameter x swept speed), stability_sweep.csv
the bisected ends stable_low, stable_high of the stable range at each parameter value (doc/csv.md:
`name [unit]` headers; an empty field: no stable speed). The optional pair marks the operating
point; swept_ring (rotor or stator) names the speed axis. Matplotlib's Agg backend: no display needed.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402


def read(path):
    """(header fields, rows as lists of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        sys.exit("plot_stability_map.py: no data in " + path)
    return rows[0], rows[1:]


def number(text):
    return float(text) if text.strip() else math.nan


def axis_label(field):
    """'clearance [m]' -> ('clearance (um)', 1e6): lengths below a millimetre in micrometres."""
    name, unit = field.split(" [")[0], field.split(" [")[1].rstrip("]")
    name = name.replace("_", " ")
    if unit == "m":
        return name + " (µm)", 1e6
    return name + ("" if unit == "-" else " (" + unit + ")"), 1.0


def main():
    if len(sys.argv) not in (4, 6, 7):
        sys.exit(__doc__)
    head, rows = read(sys.argv[1])
    label, scale = axis_label(head[0])
    values = sorted({float(r[0]) for r in rows})
    speeds = sorted({float(r[1]) for r in rows})
    iv = {v: i for i, v in enumerate(values)}
    iw = {w: j for j, w in enumerate(speeds)}
    grid = [[math.nan] * len(values) for _ in speeds]
    for r in rows:
        grid[iw[float(r[1])]][iv[float(r[0])]] = float(r[3])

    fig, ax = plt.subplots(figsize=(7, 5))
    x = [v * scale for v in values]
    ax.pcolormesh(x, speeds, grid, shading="nearest", vmin=0, vmax=1,
                  cmap=ListedColormap(["#f4c7c3", "#c9e7c4"]), rasterized=True)
    _, sweep = read(sys.argv[2])
    sv = [float(r[0]) * scale for r in sweep]
    low = [number(r[1]) for r in sweep]
    high = [number(r[2]) for r in sweep]
    low_edge = [r[3].strip() == "1" for r in sweep]
    high_edge = [r[4].strip() == "1" for r in sweep]
    ax.plot(sv, [l if not e else math.nan for l, e in zip(low, low_edge)], "k.-", lw=1.2,
            ms=4, label="threshold speed (lower end of the stable range)")
    ax.plot(sv, [h if not e else math.nan for h, e in zip(high, high_edge)], "k.--", lw=1.2,
            ms=4, label="threshold speed (upper end of the stable range)")
    if len(sys.argv) >= 6:
        ax.plot([float(sys.argv[4]) * scale], [float(sys.argv[5])], "k*", ms=12,
                label="operating point")
    ax.fill_between([], [], color="#c9e7c4", label="stable")
    ax.fill_between([], [], color="#f4c7c3", label="unstable")
    ax.set_xlabel(label)
    ax.set_ylabel((sys.argv[6] if len(sys.argv) == 7 else "swept") + " speed (rad/s)")
    ax.set_xlim(min(x), max(x))
    ax.set_title("stability map", fontsize=10)
    ax.legend(loc="best", fontsize=8, framealpha=0.9)
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=120)


if __name__ == "__main__":
    main()
