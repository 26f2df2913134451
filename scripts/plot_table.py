#!/usr/bin/env python3
"""Film coefficients, force and leakage of a `sealfe table` run against the rotor speed.

usage: plot_table.py coefficients.csv coefficients.png

Reads the table of `sealfe table` (doc/csv.md: `name [unit]` headers), keeps its grid rows that
computed (role = grid, status = ok) and draws against rotor_speed: axial stiffness and damping
K_z_z, D_z_z; tilt stiffness and damping, direct (K_tx_tx, D_tx_tx) and cross-coupled (K_tx_ty,
D_tx_ty); the axial film force force_z; the leakage through the inner circle leakage_inner. One
curve per value of the table's other swept quantities (at most 8 shown). Needs at least two rotor
speeds. Matplotlib's Agg backend: no display needed.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OPERATING_POINT = ["stator_speed", "clearance", "coning", "tilt", "pressure_difference",
                   "viscosity", "tilt_angle", "inner_pressure", "inner_radius", "outer_radius"]
# how a swept quantity is named in a legend: (label, scale, unit)
LEGEND = {"clearance": ("C0", 1e6, "µm"), "coning": ("coning", 1e3, "mrad"),
          "tilt": ("tilt", 1e3, "mrad"), "pressure_difference": ("po - pi", 1e-6, "MPa"),
          "viscosity": ("viscosity", 1e3, "mPa s"), "stator_speed": ("stator speed", 1, "rad/s"),
          "tilt_angle": ("tilt angle", 1, "rad"), "inner_pressure": ("pi", 1e-6, "MPa"),
          "inner_radius": ("ri", 1e3, "mm"), "outer_radius": ("ro", 1e3, "mm")}
# panel: (columns with line styles, scale, y label[, column whose 1% the y range covers at least])
PANELS = [
    ([("K_z_z", "-")], 1e-6, "axial stiffness $K_{zz}$ (MN/m)"),
    ([("D_z_z", "-")], 1e-3, "axial damping $D_{zz}$ (kN s/m)"),
    ([("K_tx_tx", "-")], 1e-3, "direct tilt stiffness $K_{xx}$ (kN m/rad)"),
    ([("K_tx_ty", "-")], 1e-3, "cross-coupled tilt stiffness $K_{xy}$ (kN m/rad)"),
    ([("D_tx_tx", "-")], 1.0, "direct tilt damping $D_{xx}$ (N m s/rad)"),
    ([("D_tx_ty", "-")], 1.0, "cross-coupled tilt damping $D_{xy}$ (N m s/rad)", "D_tx_tx"),
    ([("force_z", "-")], 1.0, "axial film force (N)"),
    ([("leakage_inner", "-")], 6e7, "leakage through $r_i$ (mL/min)"),
]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(f)]
    rows = [r for r in rows if r["role"] == "grid" and r["status"] == "ok"]
    if len({r["rotor_speed"] for r in rows}) < 2:
        sys.exit("plot_table.py: the table in " + sys.argv[1] + " does not sweep the rotor speed")
    swept = [c for c in OPERATING_POINT if c in rows[0] and len({r[c] for r in rows}) > 1]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(float(r[c]) for c in swept), []).append(r)
    keys = sorted(groups)
    if len(keys) > 8:  # a readable legend: eight curves spread over the others
        keys = [keys[round(i * (len(keys) - 1) / 7)] for i in range(8)]

    fig, axes = plt.subplots(4, 2, figsize=(10, 12), sharex=True)
    for ax, (columns, scale, ylabel, *reference) in zip(axes.flat, PANELS):
        for k, key in enumerate(keys):
            g = sorted(groups[key], key=lambda r: float(r["rotor_speed"]))
            w = [float(r["rotor_speed"]) for r in g]
            for column, style in columns:
                label = None
                if style == "-":
                    label = ", ".join("%s = %.4g %s" % (LEGEND[c][0], v * LEGEND[c][1],
                                                        LEGEND[c][2])
                                      for c, v in zip(swept, key)) or None
                ax.plot(w, [scale * float(r[column]) for r in g], style, color="C%d" % k,
                        marker="o", ms=3, label=label)
        if reference:  # a quantity that may be round-off only: at least +-1% of the reference
            r = 0.01 * scale * max(abs(float(row[reference[0]])) for row in rows)
            lo, hi = ax.get_ylim()
            ax.set_ylim(min(lo, -r), max(hi, r))
        ax.set_ylabel(ylabel, fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("rotor speed (rad/s)")
    if swept:
        axes[0, 0].legend(fontsize=8, loc="best")
    fig.suptitle("film coefficients against rotor speed (" + sys.argv[1].split("/")[-1] + ")",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
