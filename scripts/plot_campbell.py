#!/usr/bin/env python3
"""Campbell diagram of a `sealfe stability` run: whirl frequency and damping ratio of every mode
against the swept speed.

usage: plot_campbell.py stability_campbell.csv stability_growth_rate.csv stability_campbell.png

Reads the two CSVs of `sealfe stability` (doc/csv.md: `name [unit]` headers). Top: the signed
whirl frequency of each mode (> 0 forward, < 0 backward whirl) with the film's mean speed
psi = (omega_rotor + omega_stator)/2, the frequency at which a film-driven mode loses its damping
(Wileman & Green Eq. 17). Bottom: the damping ratio -Re(lambda)/|lambda|; the seal is unstable
where a mode's ratio is below zero (shaded). Matplotlib's Agg backend: no display needed.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    """Columns as lists of floats keyed by the name without its unit."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("plot_campbell.py: no data in " + path)
    return {k.split(" [")[0]: [float(r[k]) for r in rows] for k in rows[0]}


def unstable_spans(speed, stable):
    """[lo, hi] runs of grid speeds where the seal is unstable (half a step beyond each end)."""
    spans, start = [], None
    step = (speed[-1] - speed[0]) / max(len(speed) - 1, 1)
    for w, s in zip(speed + [None], stable + [1.0]):
        if w is not None and s < 0.5 and start is None:
            start = w
        elif (w is None or s >= 0.5) and start is not None:
            end = w - step if w is not None else speed[-1]
            spans.append((max(start - step / 2, speed[0]), min(end + step / 2, speed[-1])))
            start = None
    return spans


def speed_label(g):
    """'stator speed (rad/s), rotor at -2000 rad/s' from which column the swept speed is."""
    for ring, other in (("stator", "rotor"), ("rotor", "stator")):
        if g[ring + "_speed"] == g["swept_speed"] and len(set(g[other + "_speed"])) == 1:
            return "%s speed (rad/s); %s speed %.6g rad/s" % (ring, other,
                                                              g[other + "_speed"][0])
    return "swept speed (rad/s)"


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    m = read(sys.argv[1])
    g = read(sys.argv[2])
    w, whirl, zeta = m["swept_speed"], m["whirl_frequency"], m["damping_ratio"]
    osc = [i for i, f in enumerate(whirl) if f != 0.0]  # real eigenvalues have no whirl
    fwd = [i for i in osc if whirl[i] > 0]
    bwd = [i for i in osc if whirl[i] < 0]
    grow = [i for i in osc if zeta[i] < 0]

    fig, ax = plt.subplots(2, 1, figsize=(7.5, 7.5), sharex=True)
    spans = unstable_spans(g["swept_speed"], g["stable"])
    for a in ax:
        for lo, hi in spans:
            a.axvspan(lo, hi, color="C3", alpha=0.12, lw=0)
    for a, y in ((ax[0], whirl), (ax[1], zeta)):
        a.scatter([w[i] for i in fwd], [y[i] for i in fwd], s=2, color="C0",
                  label="forward whirl")
        a.scatter([w[i] for i in bwd], [y[i] for i in bwd], s=2, color="C1",
                  label="backward whirl")
        if grow:
            a.scatter([w[i] for i in grow], [y[i] for i in grow], s=6, color="C3",
                      marker="x", lw=0.8, label="growing mode")
    psi = [(r + s) / 2 for r, s in zip(g["rotor_speed"], g["stator_speed"])]
    ax[0].plot(g["swept_speed"], psi, "k--", lw=1,
               label="mean speed $(\\omega_{rotor} + \\omega_{stator})/2$")
    ax[0].axhline(0, color="0.5", lw=0.6)
    ax[0].set_ylabel("whirl frequency (rad/s)\n> 0 forward, < 0 backward")
    ax[1].axhline(0, color="k", lw=0.8)
    z = [zeta[i] for i in osc] or zeta
    lo, hi = min(z), max(z)
    pad = 0.08 * max(hi - lo, 1e-3)
    ax[1].set_ylim(lo - pad, min(hi + pad, 1.0))
    ax[1].set_ylabel("damping ratio $-\\mathrm{Re}\\,\\lambda/|\\lambda|$ (-)")
    ax[1].set_xlabel(speed_label(g))
    if spans:
        ax[1].plot([], [], color="C3", alpha=0.25, lw=8, label="unstable speeds")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(loc="best", fontsize=8, markerscale=3)
    ax[0].set_title("Campbell diagram", fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=120)


if __name__ == "__main__":
    main()
