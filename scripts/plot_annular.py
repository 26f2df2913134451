#!/usr/bin/env python3
"""Plots the optimum annular seals of `sealfe annular` against Lambda = f L / C2, like
Fleming's Figs. 2-8 (NASA TM X-73654).

Usage: plot_annular.py annular_lambda_sweep.csv [output.png]

The CSV has one row per Lambda and configuration (straight; tapered and stepped seals optimised
for stiffness K or stiffness per leakage K/M, stepped with the step position gamma free or
bounded). Writes a PNG with eight panels: the optimum clearance ratios H (Figs. 2, 3), the
optimum step position (Fig. 4), the dimensionless stiffness (Figs. 5, 6), the dimensionless
leakage (Figs. 7, 8) and the stiffness gain over the straight seal.
"""
import csv
import os
import sys


def read_rows(path):
    with open(path, newline="") as f:
        # "lambda [-]" -> "lambda" (doc/csv.md)
        rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(f)]
    for r in rows:
        for key in ("lambda", "step_ratio_upper_bound", "clearance_ratio", "step_ratio",
                    "stiffness_dimensionless", "leakage_dimensionless",
                    "stiffness_ratio_to_straight", "leakage_ratio_to_straight"):
            r[key] = float(r[key])
    return rows


def curves(rows):
    """Groups the rows into labelled curves: {label: (configuration, objective, bound, rows)}."""
    groups = {}
    for r in rows:
        key = (r["configuration"], r["objective"], r["step_ratio_upper_bound"])
        groups.setdefault(key, []).append(r)
    for key in groups:
        groups[key].sort(key=lambda r: r["lambda"])
    return groups


def label(key):
    configuration, objective, bound = key
    if configuration == "straight":
        return "straight"
    text = {"stiffness": "max K", "stiffness per leakage": "max K/M"}[objective]
    if configuration == "tapered":
        text = "tapered, " + text
    if configuration == "stepped":
        text = "stepped, " + text
        text += ", γ free" if bound >= 1 else f", γ ≤ {bound:g}"
    return text


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) == 3 else os.path.splitext(path)[0] + ".png"
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.ticker
    except ImportError:
        print("plot_annular.py: matplotlib is not available for " + sys.executable,
              file=sys.stderr)
        return 1

    groups = curves(read_rows(path))
    styles = {"stiffness": "-", "stiffness per leakage": "--", "none": ":"}

    def plot(ax, configurations, column, ylabel, title, straight=False):
        for key, rows in sorted(groups.items()):
            if key[0] not in configurations and not (straight and key[0] == "straight"):
                continue
            colour = {"straight": "k", "tapered": "C2"}.get(key[0], "C0" if key[2] >= 1 else "C1")
            ax.plot([r["lambda"] for r in rows], [r[column] for r in rows],
                    styles[key[1]], color=colour, label=label(key))
        ax.set_xscale("log")
        ax.set_xlabel("dimensionless seal length Λ = fL/C₂")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)

    fig, axes = plt.subplots(2, 4, figsize=(18, 8.5))
    plot(axes[0, 0], ("tapered",), "clearance_ratio", "clearance ratio H = C₁/C₂",
         "Optimum clearance ratio, tapered seal (Fig. 2)")
    plot(axes[0, 1], ("stepped",), "clearance_ratio", "clearance ratio H = C₁/C₂",
         "Optimum clearance ratio, stepped seal (Fig. 3)")
    plot(axes[0, 2], ("stepped",), "step_ratio", "step position γ = L₁/L",
         "Optimum step length, stepped seal (Fig. 4)")
    plot(axes[0, 3], ("tapered", "stepped"), "stiffness_ratio_to_straight",
         "K / K(straight, same C₂)", "Stiffness gain over the straight seal")
    plot(axes[1, 0], ("tapered",), "stiffness_dimensionless", "K̄ = K C₂ / ((p₀ − p_L) L D)",
         "Stiffness, tapered and straight seals (Fig. 5)", straight=True)
    plot(axes[1, 1], ("stepped",), "stiffness_dimensionless", "K̄ = K C₂ / ((p₀ − p_L) L D)",
         "Stiffness, stepped and straight seals (Fig. 6)", straight=True)
    plot(axes[1, 2], ("tapered",), "leakage_dimensionless", "M̄ = M / (π D C₂ √((p₀ − p_L) ρ))",
         "Flow, tapered and straight seals (Fig. 7)", straight=True)
    plot(axes[1, 3], ("stepped",), "leakage_dimensionless", "M̄ = M / (π D C₂ √((p₀ − p_L) ρ))",
         "Flow, stepped and straight seals (Fig. 8)", straight=True)
    axes[0, 3].set_yscale("log")
    axes[0, 3].yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    axes[0, 3].yaxis.set_minor_formatter(matplotlib.ticker.ScalarFormatter())
    fig.suptitle("sealfe annular: optimum high-stiffness seals (Fleming, NASA TM X-73654)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("plot_annular.py: wrote " + out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
