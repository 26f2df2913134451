#!/usr/bin/env python3
"""Picture of the cells of a gmsh 2.2 ASCII mesh (e.g. the one `Discretization/Mesh size`
generates with the dimple circles as mesh lines), in a sector of the dam (outside CI; needs
matplotlib).

usage: plot_msh.py mesh.msh output.png [theta_min theta_max (degrees)]
"""
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection


def read(path):
    """Nodes {tag: (x, y)} and quadrilaterals [(tag, tag, tag, tag)] of a gmsh 2.2 ASCII file."""
    nodes, quads, section = {}, [], None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("$"):
                section = None if line.startswith("$End") else line[1:]
                continue
            parts = line.split()
            if section == "Nodes" and len(parts) == 4:
                nodes[int(parts[0])] = (float(parts[1]), float(parts[2]))
            elif section == "Elements" and len(parts) > 3 and parts[1] == "3":
                quads.append(tuple(int(t) for t in parts[-4:]))
    return nodes, quads


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    nodes, quads = read(sys.argv[1])
    t0, t1 = (math.radians(float(a)) for a in sys.argv[3:5]) if len(sys.argv) == 5 else (-math.pi, math.pi)
    segments = []
    for q in quads:
        xy = [nodes[t] for t in q]
        cx, cy = sum(p[0] for p in xy) / 4, sum(p[1] for p in xy) / 4
        if t0 <= math.atan2(cy, cx) <= t1:
            segments += [(xy[k], xy[(k + 1) % 4]) for k in range(4)]
    fig, ax = plt.subplots(figsize=(10, 10 * 0.45))
    ax.add_collection(LineCollection(segments, linewidths=0.4, colors="k"))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"{len(quads)} quadrilaterals ({sys.argv[1].split('/')[-1]})")
    fig.savefig(sys.argv[2], dpi=200, bbox_inches="tight")


if __name__ == "__main__":
    main()
