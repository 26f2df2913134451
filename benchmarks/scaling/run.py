#!/usr/bin/python3
"""Scaling benchmark of the sealfe FE Reynolds solver (issue 13, "Scale and speed").

    /usr/bin/python3 benchmarks/scaling/run.py [--quick] [--sealfe build/sealfe]

Case: benchmarks/reynolds_speed/case.prm (the Varney & Green seal tilted to eps = 0.5), with
`Error estimate = false`, `Write fields = false`. Runs
  1. the CG + AMG ladder: degrees 1-3, aspects Ntheta/Nr = 1, 2, 16, 32, sizes 1e4 .. ~1e6 dofs
     (`Linear solver = cg-amg`), recording dofs, CG iterations, process and solve-stage time;
  2. JFO against full film on the same mesh (`Linear solver = auto`), degree 2, aspect 2 and
     prm/wavy_jfo.prm, recording the time ratio, Newton iterations and factorisations.
Writes benchmarks/scaling/scaling.csv and scaling.png (time against dofs, CG iterations against
dofs per aspect). Each run once (the machine is shared: treat times as upper bounds).
"""
import argparse, csv, json, os, shutil, subprocess, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
BASE = open(os.path.join(REPO, "benchmarks", "reynolds_speed", "case.prm")).read()


def run(sealfe, work, k, nr, nt, solver="cg-amg", cavitation="none", base=BASE):
    out = tempfile.mkdtemp(dir=work)
    prm = base + f"""
set Output directory = {out}
subsection Discretization
  set Polynomial degree = {k}
  set Radial cells = {nr}
  set Circumferential cells = {nt}
  set Global refinements = 0
  set Linear solver = {solver}
  set Error estimate = false
end
subsection Cavitation
  set Model = {cavitation}
end
subsection Output
  set Write fields = false
end
"""
    path = out + ".prm"
    open(path, "w").write(prm)
    t = time.perf_counter()
    r = subprocess.run([sealfe, "solve", path], capture_output=True, text=True, timeout=1800)
    wall = time.perf_counter() - t
    if r.returncode:
        return {"error": r.stderr.strip()[-300:], "process_wall": wall}
    s = json.load(open(os.path.join(out, "summary.json")))
    shutil.rmtree(out, ignore_errors=True)
    st = s.get("stage_wall_time", {})
    ls = s.get("linear_solver", {})
    return {"dofs": s["dofs"], "process_wall": round(wall, 3), "inprocess": s.get("wall_time"),
            "solve": st.get("solve", 0), "cavitation_time": st.get("cavitation", 0),
            "linear_setup": st.get("linear solver setup", 0),
            "cg_iterations": ls.get("krylov_iterations"), "method": ls.get("method"),
            "factorizations": ls.get("factorizations"),
            "newton": s.get("cavitation", {}).get("nonlinear_iterations"),
            "newton_steps": s.get("cavitation", {}).get("newton_steps"),
            "active_set_rounds": s.get("cavitation", {}).get("active_set_rounds"),
            "coarse_factorizations": s.get("cavitation", {}).get("coarse_level_factorizations"),
            "force_z": s["force_z"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--jfo-only", action="store_true",
                    help="only the JFO study; its rows replace the JFO rows of scaling.csv")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="sealfe-scaling-")
    max_dofs = 70000 if a.quick else 1_100_000
    rows = []
    for k in ((1, 2, 3) if not a.jfo_only else ()):
        for aspect in (1, 2, 16, 32):
            nr = 8
            while True:
                nt = aspect * nr
                dofs = (k * nr + 1) * k * nt
                if dofs > max_dofs:
                    break
                if dofs >= 10000:
                    r = run(a.sealfe, work, k, nr, nt)
                    r.update(study="amg", degree=k, aspect=aspect, nr=nr, nt=nt)
                    print(r, flush=True)
                    rows.append(r)
                nr *= 2
    wavy = open(os.path.join(REPO, "prm", "wavy_jfo.prm")).read()
    # 1e4 .. 1e6 dofs (issue 13: JFO at most 3x the full film at every size)
    for name, base, meshes in (("tilted VG", BASE, [(2, 32, 64), (2, 64, 128), (2, 128, 256),
                                                    (2, 256, 512), (2, 256, 1024)]),
                               ("wavy_jfo", wavy, [(2, 8, 256), (2, 16, 512), (2, 32, 1024),
                                                   (2, 64, 2048), (2, 64, 4096)])):
        for (k, nr, nt) in meshes[: 2 if a.quick else 5]:
            full = run(a.sealfe, work, k, nr, nt, "auto", "none", base)
            jfo = run(a.sealfe, work, k, nr, nt, "auto", "jfo", base)
            r = dict(jfo, study="jfo " + name, degree=k, nr=nr, nt=nt,
                     full_film_wall=full.get("process_wall"),
                     full_film_inprocess=full.get("inprocess"),
                     jfo_ratio_process=jfo.get("process_wall", 0) / full.get("process_wall", 1),
                     jfo_ratio_inprocess=(jfo.get("inprocess") or 0) / (full.get("inprocess") or 1))
            print(r, flush=True)
            rows.append(r)
    path = os.path.join(HERE, "scaling.csv")
    if a.jfo_only and os.path.exists(path):
        # keep the AMG rows of the last full run
        old = [r for r in csv.DictReader(open(path)) if not r["study"].startswith("jfo")]
        rows = old + rows
    keys = sorted({k for r in rows for k in r})
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    try:
        if a.jfo_only:
            raise ImportError  # the plot is of the AMG ladder: keep the last one
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
        for k in (1, 2, 3):
            for aspect in (1, 2, 16, 32):
                sel = [r for r in rows if r["study"] == "amg" and r["degree"] == k
                       and r["aspect"] == aspect and "dofs" in r]
                if not sel:
                    continue
                lab = f"k={k}, Nθ/Nr={aspect}"
                ax[0].loglog([r["dofs"] for r in sel], [r["process_wall"] for r in sel], "o-",
                             label=lab)
                ax[1].semilogx([r["dofs"] for r in sel], [r["cg_iterations"] for r in sel],
                               "o-", label=lab)
        ax[0].set_xlabel("dofs"); ax[0].set_ylabel("process wall time [s]")
        ax[1].set_xlabel("dofs"); ax[1].set_ylabel("CG iterations (rtol 1e-12)")
        ax[1].axhline(25, color="k", ls=":")
        ax[1].legend(fontsize=6, ncol=2)
        fig.tight_layout()
        fig.savefig(os.path.join(HERE, "scaling.png"), dpi=110)
    except ImportError:
        print("no plot written")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
