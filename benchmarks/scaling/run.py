#!/usr/bin/python3
"""Scaling benchmark of the sealfe FE Reynolds solver (issue 13, "Scale and speed").

    /usr/bin/python3 benchmarks/scaling/run.py [--quick] [--parts amg,gmg,coefficients,ranks,jfo,jforanks] [--sealfe build/sealfe]

Case: benchmarks/reynolds_speed/case.prm (the Varney & Green seal tilted to eps = 0.5), with
`Error estimate = false`, `Write fields = false`. Runs
  1. amg: the CG + AMG ladder, degrees 1-3, aspects Ntheta/Nr = 1, 2, 16, 32, sizes 1e4 .. 1.1e6
     dofs (degree 2: to 4.3e6), `Linear solver = cg-amg`, one rank, recording dofs, CG
     iterations, process and stage times;
  1b. gmg: the same ladder with `Linear solver = cg-gmg` (geometric multigrid on the levels of
     the built-in annulus, source/film/film_multigrid.cc), degree 2 to 4.3e6 dofs;
  1c. coefficients: the gmg ladder with `sealfe coefficients` (stiffness and damping by the
     perturbation method: with CG three adjoint solves, one per load, with the operating point's
     V-cycle), recording the CG iterations of the operating point and the most of any of the
     coefficient set's solves,
     and the coefficient set's time against the solve's (coefficient_cost_ratio);
  2. ranks: the full-film size ladder, degree 2, Ntheta/Nr = 16 (the 1.05e6-dof mesh 128 x 2048
     of issue 13 is on it), 4e3 .. 4.2e6 dofs, on 1 and 2 MPI ranks (`mpirun -np 2`) with the
     default `Linear solver = auto` (direct below 1.5e5 dofs, else CG + geometric multigrid), with
     the time exponent fitted from 1e5 dofs up (the CG + AMG rows of this ladder on 1 and 2 ranks,
     study amg, are those of an earlier run and kept);
  3. jfo: JFO against full film on the same mesh (`Linear solver = auto`), degree 2, aspect 2
     and prm/wavy_jfo.prm, recording the time ratio, Newton iterations and factorisations;
  4. jforanks: JFO on the tilted seal, 1.3e5, 5.3e5 and 1.05e6 dofs, on 1 and 2 MPI ranks.
Writes benchmarks/scaling/scaling.csv (each row with the `cpu` it ran on; rows of earlier runs
without it predate that column) and scaling.png (process time against dofs; CG iterations
against dofs per degree and aspect; CG iterations against the aspect; the same for the
coefficient set's linearised solves). Each run once (the machine is shared: treat times as upper
bounds; iteration counts are exact). --quick: up to 7e4 dofs (about a minute); the full run takes
about 30 minutes on the 2-core machine.
"""
import argparse, csv, json, math, os, re, shutil, subprocess, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
BASE = open(os.path.join(REPO, "benchmarks", "reynolds_speed", "case.prm")).read()


MPIRUN = ["mpirun", "--oversubscribe", "-np", "2"]
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(sealfe, work, k, nr, nt, solver="cg-amg", cavitation="none", base=BASE, ranks=1, env=None,
        command="solve", extra=""):
    """One `sealfe solve` (or `command`, e.g. coefficients) of `base` on an nr x nt mesh of
    degree k (no error estimate, no fields), timed from outside; `env` replaces the environment
    (default MPI_ENV); `extra` is appended to the parameter file (the last `set` of an entry
    wins: e.g. fields on)."""
    out = tempfile.mkdtemp(dir=work)
    if command == "coefficients":
        # `sealfe coefficients` has no film-model choice (it is the FE solve) and writes no fields
        base, n = re.subn(r"subsection (Film model|Output)\n.*?\nend\n", "", base, flags=re.S)
        assert n == 2, "case.prm: the Film model and Output subsections were not found"
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
""" + ("" if command == "coefficients" else """subsection Output
  set Write fields = false
end
""") + extra
    path = out + ".prm"
    open(path, "w").write(prm)
    t = time.perf_counter()
    cmd = (MPIRUN if ranks > 1 else []) + [sealfe, command, path]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=1800, env=env or MPI_ENV)
    wall = time.perf_counter() - t
    if r.returncode:
        return {"error": r.stderr.strip()[-300:], "process_wall": wall}
    s = json.load(open(os.path.join(out, "summary.json")))
    shutil.rmtree(out, ignore_errors=True)
    st = s.get("stage_wall_time", {})
    ls = s.get("linear_solver", {})
    cav = s.get("cavitation", {})
    coefficient_solves = s.get("coefficient_linear_solver", {})
    # `sealfe coefficients` times the whole operating-point run as its "solve" stage and has no
    # finer stages: those columns stay empty in its rows (operating_point_time holds the run)
    coefficients = command == "coefficients"
    stage = (lambda key: None) if coefficients else (lambda key: st.get(key, 0))
    row = {"dofs": s["dofs"], "ranks": ranks, "process_wall": round(wall, 3),
           "inprocess": s.get("wall_time"), "setup": stage("setup"),
           "assemble": stage("assemble"), "loads": stage("loads"),
           "solve": stage("solve"), "cavitation_time": stage("cavitation"),
           "linear_setup": stage("linear solver setup"),
           "operating_point_time": st.get("solve") if coefficients else None,
           "cg_iterations": ls.get("krylov_iterations"), "method": ls.get("method"),
           "factorizations": ls.get("factorizations"),
           "workspace_retries": ls.get("workspace_retries"),
           "newton": cav.get("nonlinear_iterations"),
           "newton_steps": cav.get("newton_steps"),
           "active_set_rounds": cav.get("active_set_rounds"),
           "coarse_factorizations": cav.get("coarse_level_factorizations"),
           "band_factorizations": cav.get("band_factorizations"),
           "low_rank_updates": cav.get("low_rank_updates"),
           "band_workspace_retries": cav.get("band_workspace_retries"),
           "coarse_workspace_retries": cav.get("coarse_level_workspace_retries"),
           "coefficients_time": st.get("coefficients"),
           "coefficient_cost_ratio": s.get("coefficient_cost_ratio"),
           "coefficient_solves": coefficient_solves.get("solves"),
           "coefficient_cg_max": coefficient_solves.get("max_krylov_iterations"),
           "coefficient_cg_total": coefficient_solves.get("krylov_iterations"),
           "force_z": s["force_z"], "moment_x": s["moment_x"],
           "blas_kernels": s.get("blas_kernels", {}).get("kernels")}
    if "output" in st:  # fields written (extra): the time of writing them
        row["output_time"] = st["output"]
    return row


def cpu_name():
    """The processor of this machine (model name, family and model from /proc/cpuinfo): rows of
    one scaling.csv may come from runs on machines of different kinds (--parts re-runs some
    studies only), and their times compare only within one kind."""
    info = {}
    try:
        for line in open("/proc/cpuinfo"):
            key, _, value = line.partition(":")
            info.setdefault(key.strip(), value.strip())
    except OSError:
        return ""
    return (f"{info.get('model name', '?')} (family {info.get('cpu family', '?')}, "
            f"model {info.get('model', '?')}, {os.cpu_count()} cores)")


def fit_exponent(rows):
    """Least-squares slope of log(process time) against log(dofs), dofs >= 1e5."""
    pts = [(math.log(r["dofs"]), math.log(r["process_wall"])) for r in rows
           if "dofs" in r and r["dofs"] >= 1e5]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def read_rows(path):
    """The rows of a scaling.csv with numbers as numbers and empty cells left out."""
    rows = []
    for r in csv.DictReader(open(path)):
        for key, v in list(r.items()):
            if v == "":
                del r[key]
            else:
                try:
                    r[key] = int(v)
                except ValueError:
                    try:
                        r[key] = float(v)
                    except ValueError:
                        pass
        rows.append(r)
    return rows


def plot(rows, studies):
    """scaling.png: one row of panels per study in `studies` (amg, gmg, coefficients)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(studies), 3, figsize=(15, 4.8 * len(studies)), squeeze=False)
    for ax, study in zip(axes, studies):
        # the CG iterations plotted: the full film's, or the most of the coefficient set's
        # (adjoint) solves
        its = "coefficient_cg_max" if study == "coefficients" else "cg_iterations"
        solver_name = "GMG" if study == "coefficients" else study.upper()
        colours = {1: "tab:blue", 2: "tab:orange", 16: "tab:green", 32: "tab:red"}
        markers = {1: "s", 2: "o", 3: "^"}
        for k in (1, 2, 3):
            for aspect in (1, 2, 16, 32):
                for ranks in (1, 2):
                    sel = sorted([r for r in rows if r["study"] == study and r["degree"] == k
                                  and r["aspect"] == aspect and r.get("ranks") == ranks
                                  and "dofs" in r], key=lambda r: r["dofs"])
                    if not sel:
                        continue
                    lab = f"k={k}, Nθ/Nr={aspect}" + (", 2 ranks" if ranks == 2 else "")
                    style = "--" if ranks == 2 else "-"
                    if study == "coefficients":
                        ax[0].semilogx([r["dofs"] for r in sel],
                                       [r["coefficient_cost_ratio"] for r in sel],
                                       markers[k] + style, color=colours[aspect], label=lab, ms=4)
                    else:
                        ax[0].loglog([r["dofs"] for r in sel], [r["process_wall"] for r in sel],
                                     markers[k] + style, color=colours[aspect], label=lab, ms=4)
                    if ranks == 1:
                        ax[1].semilogx([r["dofs"] for r in sel], [r[its] for r in sel],
                                       markers[k] + "-", color=colours[aspect], label=lab, ms=4)
        if study == "gmg":
            # the rank ladders on 1 and 2 ranks: full film (k = 2, aspect 16, `auto`: direct
            # below 1.5e5 dofs) and JFO (tilted VG, `auto`)
            for ranks, style in ((1, "-"), (2, "--")):
                for ladder, marker, colour, name in (
                        ("ranks", "D", "k", "k=2, Nθ/Nr=16, auto"),
                        ("jforanks", "P", "tab:purple", "JFO tilted VG, auto")):
                    sel = sorted([r for r in rows if r["study"] == ladder and r.get("ranks") == ranks
                                  and "dofs" in r], key=lambda r: r["dofs"])
                    if sel:
                        ax[0].loglog([r["dofs"] for r in sel], [r["process_wall"] for r in sel],
                                     marker + style, color=colour, ms=4,
                                     label=f"{name}, {ranks} rank" + ("s" if ranks > 1 else ""))
        # reference slope 1 (time proportional to dofs) through the 1.05e6-dof point
        ref = [r for r in rows if r["study"] == study and r.get("nr") == 128 and r.get("aspect") == 16
               and r.get("degree") == 2 and r.get("ranks") == 1 and "dofs" in r]
        if ref and study != "coefficients":
            x0, y0 = ref[0]["dofs"], ref[0]["process_wall"]
            xs = [1e4, 5e6]
            ax[0].loglog(xs, [y0 * x / x0 for x in xs], "k:", lw=1, label="∝ dofs")
        # CG iterations against the aspect, at comparable sizes: the mesh of each degree and
        # aspect nearest (in log) to 3e4, 2.5e5 and 1e6 dofs
        for target, style in ((3e4, ":"), (2.5e5, "--"), (1e6, "-")):
            for k in (1, 2, 3):
                pts = []
                for aspect in (1, 2, 16, 32):
                    sel = [r for r in rows if r["study"] == study and r["degree"] == k
                           and r["aspect"] == aspect and r.get("ranks") == 1 and "dofs" in r]
                    if sel:
                        best = min(sel, key=lambda r: abs(math.log(r["dofs"] / target)))
                        if abs(math.log(best["dofs"] / target)) < math.log(2.5):
                            pts.append((aspect, best[its]))
                if pts:
                    ax[2].semilogx([p[0] for p in pts], [p[1] for p in pts], markers[k] + style,
                                   label=f"k={k}, ~{target:.0e} dofs", base=2)
        what = "CG iterations per adjoint solve (most of 3)" if study == "coefficients" else "CG iterations"
        topic = "coefficient set" if study == "coefficients" else f"CG + {solver_name}"
        ax[0].set_xlabel("dofs")
        if study == "coefficients":
            ax[0].set_ylabel("coefficient set time / operating-point solve time")
            ax[0].set_title("coefficient set (3 adjoint solves, CG + GMG) against its solve",
                            fontsize=9)
            ax[0].axhline(1.5, color="k", ls=":", lw=1)  # the coefficient set's target
            ax[0].set_ylim(bottom=0)
        else:
            ax[0].set_ylabel("whole-process wall time [s]")
            ax[0].set_title(f"full film, CG + {study.upper()} (one run each, shared machine)"
                            + ("; rank ladders of full film and JFO" if study == "gmg" else ""),
                            fontsize=9)
        ax[0].legend(fontsize=6, ncol=2)
        ax[1].set_xlabel("dofs"); ax[1].set_ylabel(what + " (relative residual 1e-12)", fontsize=8)
        ax[1].set_title(f"{topic}: {what} against size", fontsize=9)
        ax[1].axhline(25, color="k", ls=":", lw=1)
        ax[1].legend(fontsize=6, ncol=2)
        ax[2].set_xlabel("cell aspect Nθ/Nr (cells around / cells across)")
        ax[2].set_ylabel(what + " (relative residual 1e-12)", fontsize=8)
        ax[2].set_title(f"{topic}: {what} against aspect", fontsize=9)
        ax[2].axhline(25, color="k", ls=":", lw=1)
        ax[2].legend(fontsize=7)
        for x in ax[1:]:
            x.set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "scaling.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--parts", default="amg,gmg,coefficients,ranks,jfo,jforanks")
    ap.add_argument("--plot-only", action="store_true", help="redraw scaling.png from scaling.csv")
    a = ap.parse_args()
    parts = [] if a.plot_only else a.parts.split(",")
    work = tempfile.mkdtemp(prefix="sealfe-scaling-")
    rows = []
    path = os.path.join(HERE, "scaling.csv")
    if a.plot_only:
        rows = read_rows(path)
    for study in [p for p in ("amg", "gmg", "coefficients") if p in parts]:
        for k in (1, 2, 3):
            max_dofs = 70000 if a.quick else (4_300_000 if k == 2 else 1_200_000)
            for aspect in (1, 2, 16, 32):
                nr = 8
                while True:
                    nt = aspect * nr
                    dofs = (k * nr + 1) * k * nt
                    if dofs > max_dofs:
                        break
                    if dofs >= 10000:
                        if study == "coefficients":
                            r = run(a.sealfe, work, k, nr, nt, "cg-gmg", command="coefficients")
                        else:
                            r = run(a.sealfe, work, k, nr, nt, "cg-" + study)
                        r.update(study=study, degree=k, aspect=aspect, nr=nr, nt=nt)
                        print(r, flush=True)
                        rows.append(r)
                    nr *= 2
    if "ranks" in parts:
        for nr in (8, 16, 32) if a.quick else (8, 16, 32, 64, 128, 256):
            for ranks in (1, 2):
                r = run(a.sealfe, work, 2, nr, 16 * nr, "auto", ranks=ranks)
                r.update(study="ranks", degree=2, aspect=16, nr=nr, nt=16 * nr)
                print(r, flush=True)
                rows.append(r)
    if "jfo" in parts:
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
    if "jforanks" in parts:
        # JFO on 1 and 2 ranks (issue 13: 2 ranks at least 1.6x faster at 1e6 dofs), tilted VG
        for (nr, nt) in [(64, 128), (128, 256)] if a.quick else [(128, 256), (256, 512), (256, 1024)]:
            for ranks in (1, 2):
                r = run(a.sealfe, work, 2, nr, nt, "auto", "jfo", BASE, ranks)
                r.update(study="jforanks", degree=2, nr=nr, nt=nt)
                print(r, flush=True)
                rows.append(r)
        one = {r["nr"] * 10000 + r["nt"]: r for r in rows
               if r.get("study") == "jforanks" and r.get("ranks") == 1 and "dofs" in r}
        for r in rows:
            if r.get("study") == "jforanks" and r.get("ranks") == 2 and "dofs" in r:
                o = one.get(r["nr"] * 10000 + r["nt"])
                if o:
                    print(f"JFO {r['dofs']} dofs: 2 ranks {o['process_wall'] / r['process_wall']:.2f}x "
                          f"faster, force_z rel. diff {abs(r['force_z'] / o['force_z'] - 1):.1e}")
    for ranks in (1, 2):
        sel = [r for r in rows if r.get("study") == "ranks" and r.get("ranks") == ranks]
        e = fit_exponent(sel)
        if e is not None:
            print(f"k=2, aspect 16, auto, {ranks} rank(s): process time ~ dofs^{e:.3f} (dofs >= 1e5)")
    one = {r["nr"]: r for r in rows if r.get("study") == "ranks" and r.get("ranks") == 1
           and "dofs" in r}
    for r in rows:
        if r.get("study") == "ranks" and r.get("ranks") == 2 and "dofs" in r and r["nr"] in one:
            o = one[r["nr"]]
            print(f"{r['dofs']} dofs: 2 ranks {o['process_wall'] / r['process_wall']:.2f}x faster, "
                  f"force_z rel. diff {abs(r['force_z'] / o['force_z'] - 1):.1e}, "
                  f"moment_x rel. diff {abs(r['moment_x'] / o['moment_x'] - 1):.1e}")
    path = os.path.join(HERE, "scaling.csv")
    if not a.plot_only:
        # this run's rows only (the kept rows of earlier runs are merged below)
        cpu = cpu_name()
        for r in rows:
            r["cpu"] = cpu
    if not a.plot_only and os.path.exists(path):
        # keep the rows of the studies not re-run this time (e.g. --parts jfo)
        ran = lambda study: study.split()[0] in parts
        rows = [r for r in read_rows(path) if not ran(r["study"])] + rows
    keys = sorted({k for r in rows for k in r})
    if not a.plot_only:
        with open(os.path.join(HERE, "scaling.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)
    studies = [st for st in ("amg", "gmg", "coefficients") if any(r["study"] == st for r in rows)]
    if not studies:
        print("no plot written: no amg, gmg or coefficients rows")
    else:
        try:
            plot(rows, studies)
        except ImportError:
            print("no plot written (no matplotlib)")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
