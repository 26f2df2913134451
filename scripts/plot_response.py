#!/usr/bin/env python3
"""Plot the relative tilt of a `sealfe response` run against speed, with the contact limit.

usage: plot_response.py response.csv response.png

Reads the CSV written by `sealfe response` (doc/csv.md: `name [unit]` headers; columns
swept_speed, relative_tilt, contact_tilt, stable, ...), draws the largest relative tilt gamma*
(mrad) against the swept speed, the face contact limit C0/ri as a horizontal line, and shades
the speeds where the seal is unstable (there the steady state is never reached). Uses matplotlib's Agg backend: no display needed.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    """Rows as dicts keyed by the column name without its unit ("relative_tilt [rad]" ->
    "relative_tilt")."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k.split(" [")[0]: v for k, v in r.items()} for r in rows]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = read(sys.argv[1])
    if not rows:
        sys.exit("plot_response.py: no data in " + sys.argv[1])
    w = [float(r["swept_speed"]) for r in rows]
    rel = [1e3 * float(r["relative_tilt"]) for r in rows]
    sync = [1e3 * float(r["relative_tilt_synchronous"]) for r in rows]
    limit = 1e3 * float(rows[0]["contact_tilt"])
    stable = [r["stable"].strip() == "1" for r in rows]

    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(w, rel, color="C0", label="relative tilt $\\gamma^*$ (largest over a revolution)")
    if any(abs(a - b) > 1e-12 * max(1.0, abs(a)) for a, b in zip(rel, sync)):
        ax.plot(w, sync, color="C0", ls="--", lw=1, label="synchronous part")
    ax.axhline(limit, color="C3", ls="-.", label="contact limit $C_0/r_i$")
    for i, s in enumerate(stable):
        if not s:
            lo = w[max(i - 1, 0)]
            hi = w[min(i + 1, len(w) - 1)]
            ax.axvspan(lo, hi, color="0.85", lw=0)
    if not all(stable):
        ax.plot([], [], color="0.85", lw=6, label="unstable (no steady state)")
    ax.set_xlabel("speed (rad/s)")
    ax.set_ylabel("relative tilt (mrad)")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
