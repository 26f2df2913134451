#!/usr/bin/python3
"""JFO against the full film with OpenBLAS's fallback kernels and with the CPU's (issue 13).

    /usr/bin/python3 benchmarks/blas_kernels/run.py [--sealfe build/sealfe] [--repeats 2] [--quick]

OpenBLAS 0.3.21 (Debian 12) falls back to its SSE3 "Prescott" kernels on a CPU it does not
recognise; sealfe then re-initialises it with the kernels the CPU supports
(source/numerics/blas_kernels.cc). `OPENBLAS_CORETYPE=Prescott` in the environment keeps the
fallback (the user's choice wins), which is how the "before" column is run with the same binary.
Per case, interleaved `--repeats` times: the full film, JFO with the fallback kernels, JFO with
the CPU's; tilted VG seal (benchmarks/reynolds_speed/case.prm) and prm/wavy_jfo.prm, degree 2,
`Linear solver = auto`, no error estimate, no fields; one and two ranks at the largest size.
Writes blas_kernels.csv (minimum over the repeats) and blas_kernels.png (factorisation time and
JFO / full-film ratio, before and after) beside this file; --plot-only redraws the PNG.
"""
import argparse, csv, os, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(REPO, "benchmarks", "scaling"))
import run as scaling  # noqa: E402  (benchmarks/scaling/run.py: one timed `sealfe solve`)

TILTED = open(os.path.join(REPO, "benchmarks", "reynolds_speed", "case.prm")).read()
WAVY = open(os.path.join(REPO, "prm", "wavy_jfo.prm")).read()
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
ENV.pop("OPENBLAS_CORETYPE", None)


def run(sealfe, work, base, nr, nt, model, kernels, ranks=1):
    """benchmarks/scaling's run, degree 2, `auto`, with the fallback kernels if asked."""
    env = dict(ENV, OPENBLAS_CORETYPE="Prescott") if kernels == "fallback" else ENV
    r = scaling.run(sealfe, work, 2, nr, nt, "auto", model, base, ranks, env)
    if "error" in r:
        raise SystemExit(f"{model} {nr} x {nt} on {ranks} ranks: {r['error']}")
    return {"dofs": r["dofs"], "process": r["process_wall"], "inprocess": r["inprocess"],
            "factorisation": r["linear_setup"], "kernels": r["blas_kernels"], "force_z": r["force_z"]}


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    labels = [f"{r['case']}\n{int(r['dofs']):,} dofs\n{int(r['ranks'])} rank{'s' if int(r['ranks']) > 1 else ''}"
              for r in rows]
    x = range(len(rows))
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.8))
    for axis, key, title in ((ax[0], "jfo_{}_factorisation [s]", "MUMPS factorisations of a JFO run [s]"),
                             (ax[1], "ratio_{}_process", "JFO / full film, whole process")):
        for shift, k, name in ((-0.2, "fallback", "OpenBLAS fallback (Prescott, SSE3)"),
                               (0.2, "cpu", f"CPU's kernels ({rows[0]['kernels']})")):
            axis.bar([i + shift for i in x], [float(r[key.format(k)]) for r in rows], 0.4, label=name)
        axis.set_xticks(list(x))
        axis.set_xticklabels(labels, fontsize=7)
        axis.set_title(title, fontsize=10)
        axis.legend(fontsize=8)
    ax[1].axhline(3, color="k", lw=0.8, ls="--")
    ax[1].text(len(rows) - 0.5, 3.05, "goal 3x", ha="right", fontsize=8)
    fig.suptitle("BLAS kernels behind MUMPS (tilted VG and wavy_jfo, degree 2, `auto`; minimum of the repeats)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "blas_kernels.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plot-only", action="store_true", help="redraw blas_kernels.png from the CSV")
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="1.3e5 dofs only")
    a = ap.parse_args()
    path = os.path.join(HERE, "blas_kernels.csv")
    if a.plot_only:
        plot(list(csv.DictReader(open(path))))
        return
    cases = [("tilted VG", TILTED, 128, 256), ("wavy_jfo", WAVY, 32, 1024)]
    if not a.quick:
        cases += [("tilted VG", TILTED, 256, 512), ("wavy_jfo", WAVY, 64, 2048),
                  ("tilted VG", TILTED, 256, 1024), ("wavy_jfo", WAVY, 64, 4096)]
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, base, nr, nt in cases:
            ranks = [1, 2] if (nr, nt) == (256, 1024) else [1]
            for rk in ranks:
                runs = {"full": [], "fallback": [], "cpu": []}
                for _ in range(a.repeats):
                    runs["full"].append(run(a.sealfe, work, base, nr, nt, "none", "cpu", rk))
                    runs["fallback"].append(run(a.sealfe, work, base, nr, nt, "jfo", "fallback", rk))
                    runs["cpu"].append(run(a.sealfe, work, base, nr, nt, "jfo", "cpu", rk))
                best = {k: min(v, key=lambda r: r["process"]) for k, v in runs.items()}
                row = {"case": name, "nr": nr, "nt": nt, "ranks": rk, "dofs": best["full"]["dofs"],
                       "kernels": best["cpu"]["kernels"],
                       "full_film_process [s]": best["full"]["process"],
                       "full_film_inprocess [s]": best["full"]["inprocess"]}
                for k in ("fallback", "cpu"):
                    row[f"jfo_{k}_process [s]"] = best[k]["process"]
                    row[f"jfo_{k}_inprocess [s]"] = best[k]["inprocess"]
                    row[f"jfo_{k}_factorisation [s]"] = best[k]["factorisation"]
                    row[f"ratio_{k}_process"] = best[k]["process"] / best["full"]["process"]
                    row[f"ratio_{k}_inprocess"] = best[k]["inprocess"] / best["full"]["inprocess"]
                row["force_z_difference"] = abs(best["cpu"]["force_z"] - best["fallback"]["force_z"]) / abs(best["cpu"]["force_z"])
                print({k: (round(v, 3) if isinstance(v, float) and v > 1e-3 else v) for k, v in row.items()}, flush=True)
                rows.append(row)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    plot(list(csv.DictReader(open(path))))


if __name__ == "__main__":
    main()
