#!/usr/bin/env python3
"""Histories of a `sealfe transient` run (transient.csv) in the manner of Green 2002 Figs. 4-5:
(a) normalised kinematics Z/C0, relative tilt ro/C0, min film/C0 against omega_ref t / 2 pi is
replaced by time; (b) coning ro/C0 and leakage; (c) film and contact forces; (d) speed, pressures.
usage: plot_transient.py transient.csv transient.png [C0 ro]"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    src, png = sys.argv[1], sys.argv[2]
    C0 = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-6
    ro = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0408
    with open(src) as f:
        rows = list(csv.reader(f))
    head, data = rows[0], [[float(x) for x in r] for r in rows[1:]]
    col = {h.split(" [")[0]: i for i, h in enumerate(head)}
    get = lambda name: [r[col[name]] for r in data]
    t = get("time")
    fig, ax = plt.subplots(4, 1, figsize=(8, 11), sharex=True)
    ax[0].plot(t, [z / C0 for z in get("axial_offset")], label="Z / C0")
    ax[0].plot(t, [g * ro / C0 for g in get("relative_tilt")], label="relative tilt ro / C0")
    ax[0].plot(t, [h / C0 for h in get("min_film")], label="h_min / C0")
    ax[0].set_ylabel("kinematics")
    ax[1].plot(t, [b * ro / C0 for b in get("coning")], label="coning ro / C0")
    ax1b = ax[1].twinx()
    ax1b.plot(t, [q * 6e7 for q in get("leakage_inner")], "C1", label="leakage (cm^3/min)")
    ax1b.set_ylabel("leakage [cm^3/min]")
    ax[1].set_ylabel("coning ro / C0")
    ax[2].plot(t, get("film_force"), label="film force")
    ax[2].plot(t, get("contact_force"), label="contact force")
    ax[2].plot(t, get("closing_force"), "--", label="closing force")
    ax[2].set_ylabel("force [N]")
    ax[3].plot(t, get("rotor_speed"), label="rotor speed [rad/s]")
    ax3b = ax[3].twinx()
    ax3b.plot(t, [p / 1e3 for p in get("outer_pressure")], "C1", label="p_o [kPa]")
    ax3b.plot(t, [p / 1e3 for p in get("inner_pressure")], "C2", label="p_i [kPa]")
    ax3b.set_ylabel("pressure [kPa]")
    ax[3].set_ylabel("speed [rad/s]")
    ax[3].set_xlabel("time [s]")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(loc="upper left", fontsize=8)
    ax1b.legend(loc="upper right", fontsize=8)
    ax3b.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=90)


if __name__ == "__main__":
    main()
