#!/usr/bin/python3
"""Accuracy per dof against the degree of the curved mapping (issue 13, "Accuracy per dof").

    /usr/bin/python3 benchmarks/mapping_degree/run.py [--sealfe build/sealfe]

The tilted Varney & Green seal of benchmarks/reynolds_speed/case.prm (full film, eps = 0.5) is
solved for degrees k = 1, 2, 3 with the mapping of degree m = k and m = k + 1 (`Mapping degree`)
on every mesh Nr x Ntheta with Nr in 4..64 and Ntheta in 8..256 (up to 2e5 dofs, direct solver).
The error is the relative error of force_z and moment_x against the Richardson reference of
benchmarks/reynolds_speed (results.json: degree 3, accurate to 1.6e-12 and 1.4e-11). Each run is
the scaling benchmark's `run()` (benchmarks/scaling/run.py) with `Mapping degree` appended.
Writes, next to this script, mapping_degree.csv (one row per run), mapping_degree.png (the error against the cells
around, one line per Nr and mapping degree) and prints:
- the circumferential order: at fixed Nr the differences of a load between Ntheta, 2 Ntheta and
  4 Ntheta cancel the radial error, and log2 of their ratio is the order of the error in dtheta;
- the fewest dofs that reach 1e-4, 1e-6 and 1e-8 in both loads, per k and m.
180 short runs, 80 s on the 2-core machine.
"""
import argparse, csv, json, math, os, shutil, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scaling"))
from run import REPO, run  # noqa: E402  (the scaling benchmark's single run of case.prm)

# the Richardson reference of benchmarks/reynolds_speed (doc/performance.md, "Reference values")
REFERENCE = json.load(open(os.path.join(REPO, "benchmarks", "reynolds_speed",
                                        "results.json")))["reference"]
RADIAL, AROUND = (4, 8, 16, 32, 64), (8, 16, 32, 64, 128, 256)
TARGETS = (1e-4, 1e-6, 1e-8)


def solve(sealfe, work, k, m, nr, nt):
    r = run(sealfe, work, k, nr, nt, solver="direct",
            extra=f"subsection Discretization\n  set Mapping degree = {m}\nend\n")
    if "error" in r:
        raise RuntimeError(r["error"])
    return {"k": k, "m": m, "nr": nr, "nt": nt, "dofs": r["dofs"], "force_z": r["force_z"],
            "moment_x": r["moment_x"], "force_error": r["force_z"] / REFERENCE["force_z"] - 1,
            "moment_error": r["moment_x"] / REFERENCE["moment_x"] - 1,
            "wall_time": r["inprocess"]}


def error(r):
    return max(abs(r["force_error"]), abs(r["moment_error"]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    args = ap.parse_args()
    work = tempfile.mkdtemp()
    rows = []
    for k in (1, 2, 3):
        for m in (k, k + 1):
            for nr in RADIAL:
                for nt in AROUND:
                    if nr * nt * k * k <= 2e5:
                        rows.append(solve(args.sealfe, work, k, m, nr, nt))
    shutil.rmtree(work, ignore_errors=True)
    keys = list(rows[0])
    with open(os.path.join(HERE, "mapping_degree.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)

    def find(k, m, nr, nt):
        return next((r for r in rows if (r["k"], r["m"], r["nr"], r["nt"]) == (k, m, nr, nt)),
                    None)

    print("Circumferential order of force_z / moment_x (Nr = 16; Ntheta, 2 Ntheta, 4 Ntheta):")
    print("| k | m | Ntheta = 8 | 16 | 32 |")
    print("|---|---|---|---|---|")
    for k in (1, 2, 3):
        for m in (k, k + 1):
            cells = []
            for nt in (8, 16, 32):
                a, b, c = (find(k, m, 16, n) for n in (nt, 2 * nt, 4 * nt))
                o = []
                for key in ("force_z", "moment_x"):
                    if None in (a, b, c) or b[key] == c[key]:
                        o.append("-")
                        continue
                    o.append(f"{math.log2(abs((a[key] - b[key]) / (b[key] - c[key]))):.2f}")
                cells.append(" / ".join(o))
            print(f"| {k} | {m} | " + " | ".join(cells) + " |")

    print("\nFewest dofs reaching a relative error in both loads, kept with twice the cells "
          "around (mesh Nr x Ntheta, its error):")
    print("| k | m | " + " | ".join(f"{t:.0e}" for t in TARGETS) + " |")
    print("|---|---|" + "---|" * len(TARGETS))
    for k in (1, 2, 3):
        for m in (k, k + 1):
            cells = []
            for t in TARGETS:
                # a mesh counts if it and the mesh with twice its cells around reach the target
                # (not a cancellation of the radial and circumferential errors at one Ntheta)
                ok = [r for r in rows if r["k"] == k and r["m"] == m and error(r) <= t
                      and find(k, m, r["nr"], 2 * r["nt"]) is not None
                      and error(find(k, m, r["nr"], 2 * r["nt"])) <= t]
                best = min(ok, key=lambda r: r["dofs"]) if ok else None
                cells.append(f"{best['dofs']} ({best['nr']} x {best['nt']}, {error(best):.1e})"
                             if best else "not reached")
            print(f"| {k} | {m} | " + " | ".join(cells) + " |")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(16, 5), sharey=True)
    colours = dict(zip(RADIAL, ("tab:gray", "tab:blue", "tab:green", "tab:orange", "tab:red")))
    for ax, k in zip(axes, (1, 2, 3)):
        for m, style in ((k, "--"), (k + 1, "-")):
            for nr in RADIAL:
                sel = sorted((r for r in rows if (r["k"], r["m"], r["nr"]) == (k, m, nr)),
                             key=lambda r: r["nt"])
                if sel:
                    ax.loglog([r["nt"] for r in sel], [error(r) for r in sel], "o" + style,
                              ms=3, color=colours[nr],
                              label=f"Nr = {nr}, m = {m}" + (" = k" if m == k else " = k + 1"))
        ax.set_title(f"Q{k} elements: dashed m = k, solid m = k + 1")
        ax.set_xlabel("cells around (Ntheta)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    axes[0].set_ylabel("max relative error of force_z, moment_x")
    fig.suptitle("Tilted VG seal (eps = 0.5), full film: with the mapping of degree k + 1 the "
                 "error stops depending on the cells around from ~16 on (the radial cells set it)")
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "mapping_degree.png"), dpi=110)


if __name__ == "__main__":
    main()
