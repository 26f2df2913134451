#!/usr/bin/python3
"""Speed-versus-error benchmark of the sealfe FE Reynolds solver (issue 2, "Speed").

Run with the system Python (it has matplotlib for the plot; the runs themselves use only the
standard library):

    /usr/bin/python3 benchmarks/reynolds_speed/run.py            # full benchmark, ~6-9 min
    /usr/bin/python3 benchmarks/reynolds_speed/run.py --quick    # smoke test, ~1 min, writes
                                                                 # nothing into doc/

Every timing is the wall time of the whole `sealfe solve` process, measured around the
subprocess here (so MPI/Trilinos start-up and tear-down are included), plus the in-process stage
times that sealfe writes into summary.json. Runs are strictly serial. See README.md.

Phases
  1. reference   degree 3 (the highest), three nested meshes below the direct-solver limit;
                 Richardson extrapolation of force_z and moment_x with the observed order.
  2. aspect scan degrees 1, 2, 3 x aspect ratios Ntheta/Nr in ASPECTS, one run per mesh up to
                 SCAN_MAX_DOFS; per degree the aspect with the lowest error for a given process
                 time is kept (score: mean log10 of the best-error-so-far envelope over the
                 common time range; error = max of the force and moment relative errors).
  3. timing      per degree, the kept aspect from ~3e2 to ~1e6 dofs, each mesh REPEATS times,
                 minimum process wall time reported (stage times are those of that fastest run).
  4. extras      bare process start-up; default mesh with Error estimate / Write fields on;
                 direct vs cg-amg around the 150000-unknown switch of `Linear solver = auto`.

Outputs
  doc/performance_reynolds.csv, doc/performance_reynolds.png,
  benchmarks/reynolds_speed/results.json (everything, incl. the scan and the extras),
  benchmarks/reynolds_speed/aspect_scan.csv, benchmarks/reynolds_speed/aspect_scan.png,
  and the generated block of doc/performance.md between the markers
  <!-- reynolds_speed:begin --> and <!-- reynolds_speed:end -->.
"""

import argparse
import csv
import hashlib
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
CASE = os.path.join(HERE, "case.prm")
DOC = os.path.join(REPO, "doc")

# FEniCS P2 reference on this machine (issue 2): relative force error -> wall time (s),
# meshing and start-up included.
FENICS = {1e-4: 4.0, 1e-5: 20.0}
TARGET_SPEEDUP = 5.0

DEGREES = (1, 2, 3)
ASPECTS = (2, 4, 8, 16, 32)       # Ntheta / Nr; 16 is sealfe's default mesh (8 x 128)
SCAN_MIN_DOFS, SCAN_MAX_DOFS = 250, 150000
TIME_MIN_DOFS, TIME_MAX_DOFS = 250, 1_300_000
REPEATS = 3
NO_REPEAT_ABOVE = 20.0            # s: a run slower than this is not repeated, and not refined
DIRECT_LIMIT = 150000             # sealfe's `Linear solver = auto` switch (reynolds_solver.cc)
REF_DEGREE, REF_ASPECT, REF_NR = 3, 4, (16, 32, 64)
ERROR_FLOOR = 1e-13               # errors are plotted no lower than this


def log(msg):
    print(msg, flush=True)


def n_dofs(degree, nr, nt):
    """Continuous Q_k on an nr x nt periodic annulus mesh."""
    return (degree * nr + 1) * (degree * nt)


class Runner:
    def __init__(self, sealfe, workdir):
        self.sealfe = sealfe
        self.workdir = workdir
        self.base = open(CASE).read()
        self.count = 0

    def prm(self, outdir, degree=None, nr=None, nt=None, solver=None,
            error_estimate=False, fields=False):
        disc = []
        if degree is not None:
            disc += [f"  set Polynomial degree = {degree}",
                     f"  set Radial cells = {nr}",
                     f"  set Circumferential cells = {nt}"]
        if solver is not None:
            disc.append(f"  set Linear solver = {solver}")
        disc.append(f"  set Error estimate = {'true' if error_estimate else 'false'}")
        return (self.base + "\n# ---- overrides appended by run.py ----\n"
                f"set Output directory = {outdir}\n"
                "subsection Discretization\n" + "\n".join(disc) + "\nend\n"
                "subsection Output\n"
                f"  set Write fields = {'true' if fields else 'false'}\n"
                "end\n")

    def once(self, env=None, **kw):
        self.count += 1
        outdir = os.path.join(self.workdir, f"run{self.count:04d}")
        path = os.path.join(self.workdir, f"run{self.count:04d}.prm")
        with open(path, "w") as f:
            f.write(self.prm(outdir, **kw))
        t0 = time.perf_counter()
        r = subprocess.run([self.sealfe, "solve", path], capture_output=True, text=True,
                           env=env, timeout=300)
        wall = time.perf_counter() - t0
        if r.returncode != 0:
            raise RuntimeError(f"sealfe solve failed ({kw}): {r.stderr.strip()}")
        with open(os.path.join(outdir, "summary.json")) as f:
            s = json.load(f)
        shutil.rmtree(outdir, ignore_errors=True)
        os.remove(path)
        return {"process_wall": wall, "summary": s}

    def timed(self, repeats=REPEATS, **kw):
        runs = []
        for i in range(repeats):
            runs.append(self.once(**kw))
            if runs[-1]["process_wall"] > NO_REPEAT_ABOVE:
                break
        best = min(runs, key=lambda r: r["process_wall"])
        best = dict(best)
        best["all_process_wall"] = [r["process_wall"] for r in runs]
        return best


def record(degree, nr, nt, res, solver_setting="auto"):
    s = res["summary"]
    st = s.get("stage_wall_time", {})
    dofs = s["dofs"]
    if solver_setting == "auto":
        used = "direct (KLU)" if dofs < DIRECT_LIMIT else "cg-amg"
    else:
        used = "direct (KLU)" if solver_setting == "direct" else "cg-amg"
    return {
        "degree": degree, "aspect": nt // nr, "radial_cells": nr, "circumferential_cells": nt,
        "cells": nr * nt, "dofs": dofs,
        "process_wall": res["process_wall"],
        "all_process_wall": res.get("all_process_wall", [res["process_wall"]]),
        "inprocess_wall": s["wall_time"],
        "setup": st.get("setup", 0.0), "assemble": st.get("assemble", 0.0),
        "solve": st.get("solve", 0.0), "loads": st.get("loads", 0.0),
        "output": st.get("output", 0.0), "error_estimate_time": st.get("error_estimate", 0.0),
        "force_z": s["force_z"], "moment_x": s["moment_x"],
        "linear_solver": used, "linear_iterations": s.get("linear_iterations"),
    }


def richardson(values, ratio=2.0, order=None):
    """values on meshes h, h/ratio, h/ratio^2 (or two of them with a given order)."""
    if order is None:
        a, b, c = values[-3:]
        order = math.log(abs((a - b) / (b - c))) / math.log(ratio)
    b, c = values[-2:]
    ext = c + (c - b) / (ratio ** order - 1.0)
    return ext, order


def rel(x, ref):
    return abs(x / ref - 1.0)


def add_errors(rows, ref):
    for r in rows:
        r["rel_err_force"] = rel(r["force_z"], ref["force_z"])
        r["rel_err_moment"] = rel(r["moment_x"], ref["moment_x"])


def levels(degree, aspect, lo, hi):
    out = []
    nr = 1
    while True:
        nt = aspect * nr
        d = n_dofs(degree, nr, nt)
        if d > hi:
            break
        if d >= lo and nr >= 2 and nt >= 8:
            out.append((nr, nt))
        nr *= 2
    return out


def envelope_score(rows_by_aspect):
    """Mean log10 of the best error reachable within time t, over the common time range."""
    pts = {}
    for a, rows in rows_by_aspect.items():
        pts[a] = sorted((r["model_time"], max(r["rel_err_force"], r["rel_err_moment"],
                                                ERROR_FLOOR)) for r in rows)
    t_lo = max(p[0][0] for p in pts.values())
    t_hi = min(p[-1][0] for p in pts.values())
    if not t_hi > t_lo:
        return None
    grid = [t_lo * (t_hi / t_lo) ** (i / 39) for i in range(40)]
    score = {}
    for a, p in pts.items():
        acc = 0.0
        for t in grid:
            acc += math.log10(min(e for (tt, e) in p if tt <= t * (1 + 1e-12)))
        score[a] = acc / len(grid)
    return score


def fit_order(rows, key, floor):
    """Observed order in h ~ dofs^(-1/2): pairwise and least squares over levels whose error
    is well above the reference accuracy."""
    pts = [(r["dofs"], r[key]) for r in rows if r[key] > floor]
    pair = []
    for (d0, e0), (d1, e1) in zip(pts, pts[1:]):
        pair.append(-2.0 * math.log(e1 / e0) / math.log(d1 / d0))
    fit = None
    if len(pts) >= 2:
        xs = [math.log(d) for d, _ in pts]
        ys = [math.log(e) for _, e in pts]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        sxx = sum((x - mx) ** 2 for x in xs)
        fit = -2.0 * sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return pair, fit


def time_to_reach(rows, target):
    ok = [r for r in rows if r["rel_err_force"] <= target]
    if not ok:
        return None
    best = min(ok, key=lambda r: r["process_wall"])
    coarsest = min(rows, key=lambda r: r["dofs"])
    return {"time": best["process_wall"], "dofs": best["dofs"],
            "mesh": f"{best['radial_cells']}x{best['circumferential_cells']}",
            "error": best["rel_err_force"], "on_coarsest": best is coarsest}


def machine_info(sealfe):
    info = {"python": sys.version.split()[0], "platform": platform.platform()}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
        info["logical_cpus"] = os.cpu_count()
        with open("/proc/meminfo") as f:
            info["memory_GiB"] = round(int(f.readline().split()[1]) / 2**20, 1)
    except OSError:
        pass
    try:
        info["debian"] = open("/etc/debian_version").read().strip()
    except OSError:
        pass
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libdeal.ii-dev"],
                             capture_output=True, text=True).stdout
        info["deal.II"] = out
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libtrilinos-ml-dev"],
                             capture_output=True, text=True).stdout
        info["trilinos"] = out
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libopenmpi3"],
                             capture_output=True, text=True).stdout
        info["openmpi"] = out
    except OSError:
        pass
    try:
        info["git_commit"] = subprocess.run(["git", "-C", REPO, "rev-parse", "HEAD"],
                                            capture_output=True, text=True).stdout.strip()
    except OSError:
        pass
    h = hashlib.sha256()
    with open(sealfe, "rb") as f:
        h.update(f.read())
    info["sealfe_sha256"] = h.hexdigest()[:16]
    info["sealfe_mtime"] = time.strftime("%Y-%m-%d %H:%M:%S",
                                         time.localtime(os.path.getmtime(sealfe)))
    return info


# ------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--quick", action="store_true",
                    help="small smoke test (max 3e4 dofs, 1 repeat); writes only to --out")
    ap.add_argument("--out", default=None, help="directory for the outputs instead of doc/")
    ap.add_argument("--replot", action="store_true",
                    help="no runs: redo table, plots and doc block from results.json")
    args = ap.parse_args()

    if args.replot:
        with open(os.path.join(args.out or HERE, "results.json")) as f:
            results = json.load(f)
        results["chosen_aspect"] = {int(k): v for k, v in results["chosen_aspect"].items()}
        results["aspect_scores"] = {int(k): {int(a): x for a, x in v.items()}
                                    for k, v in results["aspect_scores"].items()}
        analyse_and_write(results, args.out or DOC, args.out or HERE)
        return

    global SCAN_MAX_DOFS, TIME_MAX_DOFS, REPEATS
    if args.quick:
        SCAN_MAX_DOFS, TIME_MAX_DOFS, REPEATS = 20000, 40000, 1
    out_doc = args.out or (tempfile.mkdtemp(prefix="reynolds_speed_quick_") if args.quick
                           else DOC)
    out_bench = args.out or (out_doc if args.quick else HERE)
    os.makedirs(out_doc, exist_ok=True)

    if not os.path.exists(args.sealfe):
        sys.exit(f"{args.sealfe} not found: cmake --build build --target sealfe")
    workdir = tempfile.mkdtemp(prefix="reynolds_speed_")
    # Snapshot the executable: other people may rebuild build/sealfe while this runs.
    sealfe = os.path.join(workdir, "sealfe")
    shutil.copy2(args.sealfe, sealfe)
    run = Runner(sealfe, workdir)
    t_start = time.perf_counter()
    machine = machine_info(sealfe)
    machine["loadavg_at_start"] = os.getloadavg()
    log(f"sealfe {args.sealfe} (sha256 {machine['sealfe_sha256']}), workdir {workdir}")

    # 0. bare process start-up ---------------------------------------------------------------
    # `sealfe --print-parameters solve` loads the same libraries and initialises MPI like a
    # solve, but builds no mesh. OMPI_MCA_pml=ob1 skips Open MPI's UCX initialisation.
    extras = {}
    env_ob1 = dict(os.environ, OMPI_MCA_pml="ob1")
    for name, env in (("default", None), ("OMPI_MCA_pml=ob1", env_ob1)):
        ts = []
        for i in range(5):
            t0 = time.perf_counter()
            subprocess.run([sealfe, "--print-parameters", "solve"], capture_output=True,
                           env=env, check=True)
            ts.append(time.perf_counter() - t0)
        extras[f"startup_print_parameters[{name}]"] = {"process_wall": min(ts), "all": ts}
        log(f"   bare start-up (sealfe --print-parameters solve), env {name}: {min(ts):.3f} s")
    startup = extras["startup_print_parameters[default]"]["process_wall"]

    # 1. reference --------------------------------------------------------------------------
    log("== reference: degree %d, aspect %d, Nr = %s" % (REF_DEGREE, REF_ASPECT, REF_NR))
    ref_rows = []
    for nr in REF_NR:
        res = run.once(degree=REF_DEGREE, nr=nr, nt=REF_ASPECT * nr, solver="direct")
        ref_rows.append(record(REF_DEGREE, nr, REF_ASPECT * nr, res, "direct"))
        log("   %4d x %5d  %8d dofs  F = %.12f  Mx = %.12f" %
            (nr, REF_ASPECT * nr, ref_rows[-1]["dofs"], ref_rows[-1]["force_z"],
             ref_rows[-1]["moment_x"]))
    ref = {}
    for key in ("force_z", "moment_x"):
        vals = [r[key] for r in ref_rows]
        ext, p = richardson(vals)
        ext_theory, _ = richardson(vals, order=2 * REF_DEGREE)
        # Accuracy: the Richardson correction of the finest value (a bound on the finest
        # solution's own error), and the spread between observed- and theoretical-order
        # extrapolation.
        acc = max(abs(ext - vals[-1]), abs(ext - ext_theory))
        ref[key] = ext
        ref[key + "_observed_order"] = p
        ref[key + "_extrapolated_order_2k"] = ext_theory
        ref[key + "_abs_accuracy"] = acc
        ref[key + "_rel_accuracy"] = acc / abs(ext)
        ref[key + "_values"] = vals
        log(f"   {key}: reference {ext:.12f} (observed order {p:.2f}, "
            f"est. rel. accuracy {acc / abs(ext):.1e})")
    ref["meshes"] = [f"{r['radial_cells']}x{r['circumferential_cells']}" for r in ref_rows]
    ref["dofs"] = [r["dofs"] for r in ref_rows]
    ref["degree"] = REF_DEGREE
    acc_floor = max(ref["force_z_rel_accuracy"], ref["moment_x_rel_accuracy"], ERROR_FLOOR)

    # 2. aspect scan ------------------------------------------------------------------------
    log("== aspect scan (one run per mesh, dofs <= %d)" % SCAN_MAX_DOFS)
    scan = []
    for d in DEGREES:
        for a in ASPECTS:
            for nr, nt in levels(d, a, SCAN_MIN_DOFS, SCAN_MAX_DOFS):
                r = record(d, nr, nt, run.once(degree=d, nr=nr, nt=nt))
                scan.append(r)
    add_errors(scan, ref)
    for r in scan:
        # Single runs on shared cores: the start-up part of the process time is the noisiest,
        # and it does not depend on the mesh. Rank aspects by in-process time + bare start-up.
        r["model_time"] = r["inprocess_wall"] + startup
        log("   k=%d %3dx%5d %8d dofs %6.2f s  eF %.2e  eM %.2e" %
            (r["degree"], r["radial_cells"], r["circumferential_cells"], r["dofs"],
             r["model_time"], r["rel_err_force"], r["rel_err_moment"]))
    chosen, scores = {}, {}
    for d in DEGREES:
        by = {a: [r for r in scan if r["degree"] == d and r["aspect"] == a] for a in ASPECTS}
        by = {a: v for a, v in by.items() if len(v) >= 2}
        sc = envelope_score(by)
        if sc is None:   # no common time range: fall back to the error at the largest mesh
            sc = {a: math.log10(max(v[-1]["rel_err_force"], v[-1]["rel_err_moment"],
                                    ERROR_FLOOR)) for a, v in by.items()}
        scores[d] = sc
        chosen[d] = min(sc, key=sc.get)
        log(f"   degree {d}: scores {', '.join(f'{a}: {s:.2f}' for a, s in sc.items())}"
            f" -> aspect {chosen[d]}")

    # 3. timing -----------------------------------------------------------------------------
    # Repeats are interleaved (pass 1 over every mesh, then pass 2, ...) so that a burst of
    # load from other users hits different meshes in different passes; the minimum is kept.
    log("== timing (min of %d interleaved passes)" % REPEATS)
    jobs = []
    for d in DEGREES:
        for nr, nt in levels(d, chosen[d], TIME_MIN_DOFS, TIME_MAX_DOFS):
            res = run.once(degree=d, nr=nr, nt=nt)
            jobs.append({"kw": dict(degree=d, nr=nr, nt=nt), "runs": [res],
                         "meta": (d, nr, nt, "auto")})
            log("   pass 1: k=%d %4dx%5d %8d dofs %7.3f s" %
                (d, nr, nt, res["summary"]["dofs"], res["process_wall"]))
            if res["process_wall"] > NO_REPEAT_ABOVE:
                log("   (slower than %.0f s: not repeated, no finer mesh)" % NO_REPEAT_ABOVE)
                break
    repeat_passes(run, jobs)
    rows = []
    for j in jobs:
        d, nr, nt, solver = j["meta"]
        r = record(d, nr, nt, best_of(j["runs"]), solver)
        add_errors([r], ref)
        rows.append(r)
        log("   k=%d %4dx%5d %8d dofs  %7.3f s (in-process %7.3f: setup %.3f assemble %.3f "
            "solve %.3f loads %.3f) %s its=%s  eF %.2e eM %.2e" %
            (d, nr, nt, r["dofs"], r["process_wall"], r["inprocess_wall"], r["setup"],
             r["assemble"], r["solve"], r["loads"], r["linear_solver"],
             r["linear_iterations"], r["rel_err_force"], r["rel_err_moment"]))

    # 4. extras -----------------------------------------------------------------------------
    log("== extras")
    jobs = []
    for name, kw in (("baseline", {}),
                     ("Error estimate = true", {"error_estimate": True}),
                     ("Write fields = true", {"fields": True}),
                     ("both", {"error_estimate": True, "fields": True}),
                     ("baseline, OMPI_MCA_pml=ob1", {"env": env_ob1})):
        jobs.append({"kw": kw, "runs": [run.once(**kw)], "meta": (2, 8, 128, "auto"),
                     "name": name, "group": "default_mesh"})
    d = 2
    for a in sorted({chosen[2], 16}):
        for nr, nt in levels(d, a, 30000, 300000 if not args.quick else 40000):
            for solver in ("direct", "cg-amg"):
                kw = dict(degree=d, nr=nr, nt=nt, solver=solver)
                jobs.append({"kw": kw, "runs": [run.once(**kw)], "meta": (d, nr, nt, solver),
                             "group": "solver"})
    # AMG at ~1e6 unknowns: the kept aspect against sealfe's default aspect 16.
    for a in sorted({chosen[2], 16}):
        for nr, nt in levels(d, a, 900000 if not args.quick else 60000,
                             TIME_MAX_DOFS if not args.quick else 70000):
            kw = dict(degree=d, nr=nr, nt=nt, solver="cg-amg")
            jobs.append({"kw": kw, "runs": [run.once(**kw)], "meta": (d, nr, nt, "cg-amg"),
                         "group": "solver"})
    repeat_passes(run, jobs)
    default_mesh, solver_cmp = {}, []
    for j in jobs:
        d, nr, nt, solver = j["meta"]
        r = record(d, nr, nt, best_of(j["runs"]), solver)
        add_errors([r], ref)
        if j["group"] == "default_mesh":
            default_mesh[j["name"]] = r
            log(f"   default mesh (k=2, 8x128, {r['dofs']} dofs) {j['name']}: process "
                f"{r['process_wall']:.3f} s, in-process {r['inprocess_wall']:.4f} s, "
                f"error_estimate {r['error_estimate_time']:.4f} s, output {r['output']:.4f} s")
        else:
            solver_cmp.append(r)
            log(f"   solver k=2 {nr}x{nt} {r['dofs']} dofs {solver}: process "
                f"{r['process_wall']:.3f} s, solve stage {r['solve']:.3f} s, its "
                f"{r['linear_iterations']}")
    extras["default_mesh"] = default_mesh
    extras["solver_comparison"] = solver_cmp

    total = time.perf_counter() - t_start
    machine["loadavg_at_end"] = os.getloadavg()
    machine["benchmark_wall_time_s"] = total
    machine["sealfe_runs"] = run.count
    log(f"== total {total:.0f} s, {run.count} sealfe runs")
    results = {"machine": machine, "reference": ref, "aspect_scores": scores,
               "chosen_aspect": chosen, "scan": scan, "timing": rows, "extras": extras,
               "fenics": {str(k): v for k, v in FENICS.items()},
               "settings": {"repeats": REPEATS, "aspects": ASPECTS, "degrees": DEGREES,
                            "scan_max_dofs": SCAN_MAX_DOFS, "time_max_dofs": TIME_MAX_DOFS,
                            "quick": args.quick}}
    analyse_and_write(results, out_doc, out_bench)
    shutil.rmtree(workdir, ignore_errors=True)


def repeat_passes(run, jobs):
    for p in range(2, REPEATS + 1):
        for j in jobs:
            if j["runs"][0]["process_wall"] <= NO_REPEAT_ABOVE:
                j["runs"].append(run.once(**j["kw"]))
        log(f"   pass {p} done")


def best_of(runs):
    best = dict(min(runs, key=lambda r: r["process_wall"]))
    best["all_process_wall"] = [r["process_wall"] for r in runs]
    return best


def analyse_and_write(results, out_doc, out_bench):
    ref, rows, scan = results["reference"], results["timing"], results["scan"]
    chosen, extras = results["chosen_aspect"], results["extras"]
    acc_floor = max(ref["force_z_rel_accuracy"], ref["moment_x_rel_accuracy"], ERROR_FLOOR)
    # analysis ------------------------------------------------------------------------------
    orders = {}
    for d in DEGREES:
        rs = [r for r in rows if r["degree"] == d]
        orders[d] = {}
        for key in ("rel_err_force", "rel_err_moment"):
            pair, fit = fit_order(rs, key, 100 * acc_floor)
            orders[d][key] = {"pairwise": pair, "fit": fit}
    # Cross-check: Richardson from the finest meshes of each timed sequence.
    cross = {}
    for d in DEGREES:
        rs = [r for r in rows if r["degree"] == d]
        if len(rs) >= 3:
            cross[d] = {}
            for key in ("force_z", "moment_x"):
                ext, _ = richardson([r[key] for r in rs][-2:], order=2 * d)
                cross[d][key] = ext
                cross[d][key + "_rel_diff"] = rel(ext, ref[key])
    reach = {}
    for d in DEGREES:
        rs = [r for r in rows if r["degree"] == d]
        reach[d] = {str(t): time_to_reach(rs, t) for t in FENICS}

    results.update({"orders": orders, "cross_check": cross, "time_to_reach": reach})
    with open(os.path.join(out_bench, "results.json"), "w") as f:
        json.dump(results, f, indent=1)

    write_csv(os.path.join(out_doc, "performance_reynolds.csv"), rows)
    write_csv(os.path.join(out_bench, "aspect_scan.csv"), scan, scan=True)
    try:
        plot(os.path.join(out_doc, "performance_reynolds.png"), rows, extras, acc_floor, chosen)
        plot_scan(os.path.join(out_bench, "aspect_scan.png"), scan, chosen)
    except ImportError as e:
        log(f"no plot ({e}); run with /usr/bin/python3")
    md = markdown(results, acc_floor)
    update_doc(os.path.join(out_doc, "performance.md"), md)
    log(f"wrote {out_doc}/performance_reynolds.csv, .png, performance.md; {out_bench}/results.json")


CSV_FIELDS = [
    ("degree", "degree", "{}"), ("aspect_ntheta_over_nr", "aspect", "{}"),
    ("radial_cells", "radial_cells", "{}"), ("circumferential_cells", "circumferential_cells", "{}"),
    ("cells", "cells", "{}"), ("dofs", "dofs", "{}"),
    ("process_wall_s", "process_wall", "{:.4f}"), ("inprocess_wall_s", "inprocess_wall", "{:.4f}"),
    ("setup_s", "setup", "{:.4f}"), ("assemble_s", "assemble", "{:.4f}"),
    ("solve_s", "solve", "{:.4f}"), ("loads_s", "loads", "{:.4f}"),
    ("force_z_N", "force_z", "{:.12g}"), ("moment_x_Nm", "moment_x", "{:.12g}"),
    ("rel_err_force_z", "rel_err_force", "{:.3e}"), ("rel_err_moment_x", "rel_err_moment", "{:.3e}"),
    ("linear_solver", "linear_solver", "{}"), ("linear_iterations", "linear_iterations", "{}"),
]


def write_csv(path, rows, scan=False):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        head = [c[0] for c in CSV_FIELDS] + (["process_wall_all_s"] if not scan else [])
        w.writerow(head)
        for r in rows:
            line = [fmt.format(r[k]) for _, k, fmt in CSV_FIELDS]
            if not scan:
                line.append(";".join(f"{t:.4f}" for t in r["all_process_wall"]))
            w.writerow(line)


COLORS = {1: "tab:blue", 2: "tab:orange", 3: "tab:green"}


def plot(path, rows, extras, floor, chosen):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(10, 5.8))
    for d in DEGREES:
        rs = [r for r in rows if r["degree"] == d]
        if not rs:
            continue
        t = [r["process_wall"] for r in rs]
        ax.loglog(t, [max(r["rel_err_force"], ERROR_FLOOR) for r in rs], "o-",
                  color=COLORS[d], label=f"k={d} force_z (Nθ/Nr={chosen[d]})")
        ax.loglog(t, [max(r["rel_err_moment"], ERROR_FLOOR) for r in rs], "s--",
                  color=COLORS[d], mfc="none", label=f"k={d} moment_x")
    ax.axhspan(ERROR_FLOOR / 3, floor, color="0.85", zorder=0,
               label="below reference accuracy")
    ft = list(FENICS.items())
    ax.plot([v for _, v in ft], [k for k, _ in ft], "r*", ms=14,
            label="FEniCS P2 reference (force)")
    ax.plot([v / TARGET_SPEEDUP for _, v in ft], [k for k, _ in ft], "r*", ms=14, mfc="none",
            label=f"target: {TARGET_SPEEDUP:.0f}× faster")
    # Process overhead: the smallest (process - in-process) time of any timed run; a more
    # robust floor than the separate bare start-up measurement on loaded cores.
    over = min(r["process_wall"] - r["inprocess_wall"] for r in rows)
    ax.axvline(over, color="0.4", ls=":", lw=1)
    ax.text(over * 1.04, 6e-2, f"process overhead (start-up + tear-down) {over:.2f} s",
            fontsize=7.5, color="0.3", va="top", ha="left")
    ax.set_xlabel("whole-process wall time of `sealfe solve` [s] (min of 3)")
    ax.set_ylabel("relative error vs Richardson reference")
    ax.set_title("sealfe FE Reynolds: Varney & Green seal, ε = 0.5 tilt, full film")
    ax.grid(True, which="both", alpha=0.3)
    for (e, tf) in ft:
        ax.annotate(f"FEniCS {e:.0e}: {tf:.0f} s", (tf, e), textcoords="offset points",
                    xytext=(-10, 9), fontsize=7.5, color="r", ha="center")
    ax.set_ylim(ERROR_FLOOR / 3, 1e-1)
    ax.set_xlim(0.2, 100)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plot_scan(path, scan, chosen):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, len(DEGREES), figsize=(13, 4.2), sharey=True)
    for ax, d in zip(axs, DEGREES):
        for a in ASPECTS:
            rs = [r for r in scan if r["degree"] == d and r["aspect"] == a]
            if not rs:
                continue
            ax.loglog([r["model_time"] for r in rs],
                      [max(r["rel_err_force"], r["rel_err_moment"], ERROR_FLOOR) for r in rs],
                      "o-" if a == chosen[d] else ".--", lw=2 if a == chosen[d] else 1,
                      label=f"Nθ/Nr = {a}")
        ax.set_title(f"degree {d} (kept: {chosen[d]})")
        ax.set_xlabel("in-process wall time + bare start-up [s] (single run)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axs[0].set_ylabel("max(rel. err force_z, moment_x)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def g(x, n=3):
    return f"{x:.{n}g}"


def markdown(R, floor):
    ref, m, ex = R["reference"], R["machine"], R["extras"]
    L = []
    L.append(f"*Generated by `benchmarks/reynolds_speed/run.py` on {time.strftime('%Y-%m-%d')}; "
             f"sealfe commit `{m.get('git_commit', '?')[:10]}` (binary sha256 "
             f"`{m['sealfe_sha256']}`), {m.get('cpu', '?')} × {m.get('logical_cpus')}, "
             f"load average {m['loadavg_at_start'][0]:.1f} at start (cores shared with "
             f"compilers), {m['sealfe_runs']} runs in {m['benchmark_wall_time_s']:.0f} s.*")
    L.append("")
    L.append("### Reference values")
    L.append("")
    L.append(f"Degree {ref['degree']}, meshes {', '.join(ref['meshes'])} (Nr × Nθ; "
             f"{', '.join(str(x) for x in ref['dofs'])} dofs, direct solver), Richardson "
             "extrapolation of the finest two with the order observed on the three:")
    L.append("")
    L.append("| load | finest three values | observed order | reference | est. rel. accuracy |")
    L.append("|---|---|---|---|---|")
    for key, unit in (("force_z", "N"), ("moment_x", "N m")):
        L.append(f"| {key} [{unit}] | {', '.join(f'{v:.12f}' for v in ref[key + '_values'])} | "
                 f"{ref[key + '_observed_order']:.2f} | **{ref[key]:.12f}** | "
                 f"{ref[key + '_rel_accuracy']:.1e} |")
    L.append("")
    L.append("Estimated accuracy = max(|reference − finest value|, |reference − extrapolation "
             "with the theoretical order 2k|). Cross-check, Richardson (order 2k) from the "
             "finest two meshes of each timed sequence:")
    L.append("")
    for d, c in R["cross_check"].items():
        L.append(f"- k = {d}: force_z {c['force_z']:.12f} (rel. diff {c['force_z_rel_diff']:.1e}), "
                 f"moment_x {c['moment_x']:.12f} (rel. diff {c['moment_x_rel_diff']:.1e})")
    L.append("")
    L.append("### Mesh aspect (Nθ / Nr)")
    L.append("")
    L.append("Score = mean log10 of the best max(force, moment) relative error reachable within "
             "a given time (in-process wall time of a single run + the bare start-up), over the "
             "time range common to all aspects (meshes up to "
             f"{R['settings']['scan_max_dofs']} dofs, i.e. all solved by KLU; lower is better; "
             "`aspect_scan.csv`, `aspect_scan.png`):")
    L.append("")
    L.append("| degree | " + " | ".join(f"Nθ/Nr = {a}" for a in ASPECTS) + " | kept |")
    L.append("|---|" + "---|" * (len(ASPECTS) + 1))
    for d, sc in R["aspect_scores"].items():
        L.append(f"| {d} | " + " | ".join(g(sc[a], 3) if a in sc else "–" for a in ASPECTS)
                 + f" | **{R['chosen_aspect'][d]}** |")
    L.append("")
    L.append("### Timing table")
    L.append("")
    L.append("Process = wall time of the whole `sealfe solve` process (minimum of "
             f"{R['settings']['repeats']}); the stage columns are sealfe's own stage times of "
             "that run; start = process − in-process (MPI/Trilinos start-up, library loading, "
             "tear-down).")
    L.append("")
    L.append("| k | Nr × Nθ | dofs | process [s] | start [s] | setup | assemble | solve | loads "
             "| solver (its) | rel. err force_z | rel. err moment_x |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in R["timing"]:
        L.append(f"| {r['degree']} | {r['radial_cells']} × {r['circumferential_cells']} | "
                 f"{r['dofs']} | {r['process_wall']:.3f} | "
                 f"{r['process_wall'] - r['inprocess_wall']:.3f} | {r['setup']:.3f} | "
                 f"{r['assemble']:.3f} | {r['solve']:.3f} | {r['loads']:.3f} | "
                 f"{r['linear_solver'].split()[0]} ({r['linear_iterations']}) | "
                 f"{r['rel_err_force']:.2e} | {r['rel_err_moment']:.2e} |")
    L.append("")
    L.append(f"Errors below ~{floor:.0e} are at the accuracy of the reference and carry no "
             "information about convergence.")
    L.append("")
    L.append("### Observed convergence orders (in h ∝ dofs^(−1/2))")
    L.append("")
    L.append("| k | force_z pairwise | force_z fit | moment_x pairwise | moment_x fit |")
    L.append("|---|---|---|---|---|")
    for d, o in R["orders"].items():
        f, mo = o["rel_err_force"], o["rel_err_moment"]
        L.append(f"| {d} | {', '.join(f'{x:.2f}' for x in f['pairwise'])} | "
                 f"{f['fit']:.2f} | {', '.join(f'{x:.2f}' for x in mo['pairwise'])} | "
                 f"{mo['fit']:.2f} |" if f["fit"] is not None and mo["fit"] is not None else
                 f"| {d} | – | – | – | – |")
    L.append("")
    L.append(f"(levels with error > 100 × the reference accuracy only.)")
    L.append("")
    L.append("### Time to reach a relative force error (whole process)")
    L.append("")
    L.append("| target | FEniCS P2 | " + " | ".join(f"sealfe k={d}" for d in DEGREES)
             + " | best speed-up | ≥ 5×? |")
    L.append("|---|---|" + "---|" * len(DEGREES) + "---|---|")
    for t, tf in FENICS.items():
        cells, best = [], None
        for d in DEGREES:
            x = R["time_to_reach"][d][str(t)]
            if x is None:
                cells.append("not reached")
                continue
            cells.append(f"{'≤ ' if x['on_coarsest'] else ''}{x['time']:.2f} s "
                         f"({x['mesh']}, {x['dofs']} dofs, err {x['error']:.1e})")
            best = x["time"] if best is None else min(best, x["time"])
        sp = tf / best if best else None
        L.append(f"| {t:.0e} | {tf:.0f} s | " + " | ".join(cells) +
                 f" | {sp:.1f}× | {'yes' if sp and sp >= TARGET_SPEEDUP else 'NO'} |"
                 if sp else f"| {t:.0e} | {tf:.0f} s | " + " | ".join(cells) + " | – | NO |")
    L.append("")
    L.append("“≤” : already reached on the coarsest mesh of that sequence.")
    L.append("")
    over = min(r["process_wall"] - r["inprocess_wall"] for r in R["timing"])
    L.append(f"Smallest process overhead (process − in-process) over all timed runs: "
             f"**{over:.3f} s**.")
    L.append("")
    L.append("### Start-up, error estimate and field output")
    L.append("")
    L.append("| run | process [s] | in-process [s] | extra stage |")
    L.append("|---|---|---|---|")
    for name in ("default", "OMPI_MCA_pml=ob1"):
        x = ex[f"startup_print_parameters[{name}]"]
        L.append(f"| `sealfe --print-parameters solve` (bare start-up), env {name} | "
                 f"{x['process_wall']:.3f} | – | – |")
    base = ex["default_mesh"]["baseline"]
    for name, r in ex["default_mesh"].items():
        extra = []
        if r["error_estimate_time"]:
            extra.append(f"error_estimate {r['error_estimate_time']:.4f} s")
        if r["output"]:
            extra.append(f"output {r['output']:.4f} s")
        L.append(f"| default mesh (k=2, 8 × 128, {r['dofs']} dofs), {name} | "
                 f"{r['process_wall']:.3f} ({r['process_wall'] - base['process_wall']:+.3f}) | "
                 f"{r['inprocess_wall']:.4f} ({r['inprocess_wall'] / base['inprocess_wall']:.2f}×) | "
                 f"{', '.join(extra) or '–'} |")
    L.append("")
    L.append("### Direct (KLU) vs CG + AMG around the `auto` switch (150000 unknowns), k = 2")
    L.append("")
    L.append("| Nθ/Nr | Nr × Nθ | dofs | solver | process [s] | solve stage [s] | iterations "
             "| rel. err force_z | rel. err moment_x |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for r in ex["solver_comparison"]:
        L.append(f"| {r['aspect']} | {r['radial_cells']} × {r['circumferential_cells']} | {r['dofs']} | "
                 f"{r['linear_solver']} | {r['process_wall']:.3f} | {r['solve']:.3f} | "
                 f"{r['linear_iterations']} | {r['rel_err_force']:.2e} | "
                 f"{r['rel_err_moment']:.2e} |")
    return "\n".join(L)


BEGIN, END = "<!-- reynolds_speed:begin -->", "<!-- reynolds_speed:end -->"


def update_doc(path, block):
    text = open(path).read() if os.path.exists(path) else (
        "# Performance\n\n## FE Reynolds solver: speed versus error\n\n"
        f"{BEGIN}\n{END}\n\n## Cavitation (JFO) cost\n\n## Coefficients cost\n")
    if BEGIN not in text:
        text += f"\n{BEGIN}\n{END}\n"
    a, rest = text.split(BEGIN, 1)
    _, b = rest.split(END, 1)
    with open(path, "w") as f:
        f.write(a + BEGIN + "\n" + block + "\n" + END + b)


if __name__ == "__main__":
    main()
