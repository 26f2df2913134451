#!/usr/bin/python3
"""Issue 13's speed goals at 1e6 dofs, measured in one run with interleaved rounds.

    /usr/bin/python3 benchmarks/scaling/goals.py [--rounds 3] [--quick] [--sealfe build/sealfe]

Each round runs every case below once, in the same order, so that a slow spell of the shared
machine falls on a whole round rather than on one side of a ratio; every ratio is taken round by
round (the JFO run against the full film of the same round, two ranks against one) and reported
as its median and range over the rounds. Times are whole process, from outside (`process_wall`),
degree 2, `Error estimate = false`, `Write fields = false` unless said.

| goal | cases (benchmarks/reynolds_speed/case.prm, the tilted VG seal; prm/wavy_jfo.prm) |
|---|---|
| full film, one rank, under 4 s | tilted, 128 x 2048 cells, 1 052 672 dofs, `auto` (cg-gmg) |
| two ranks at least 1.6x one rank, same force_z (1e-10) | the same on `mpirun -np 2` |
| (reported) one rank held to one thread, and two ranks against it | the same, `DEAL_II_NUM_THREADS=1` (full film and JFO) |
| fields at most 20 % of the solve | the same with `Write fields = true`: output / (in-process - output) |
| JFO at most 3x the full film of its mesh | tilted 256 x 1024 (1 050 624 dofs); wavy_jfo 64 x 4096 (1 056 768) |
| JFO on two ranks at least 1.6x one rank, same force_z | tilted 256 x 1024 |
| a bare `sealfe solve` under 0.3 s | the default seal, no parameter file |
| sweep points per second (reported) | `sealfe table prm/table.prm` |

The time-against-dofs exponent and the CG iteration counts over sizes, aspects and degrees are
the size ladder's (run.py). Writes goals.csv (one row per run: round, case, times, force_z) and
goals_summary.csv (one row per goal: median, min, max, target, met) next to this script, and
prints the summary as a table. --quick: meshes 16 times smaller and one round (about ten
seconds), printed only; its verdicts are not issue 13's (the goals are stated at 1e6 dofs). The full run takes about
80 s a round on the 2-core machine.
"""
import argparse, csv, json, os, shutil, statistics, subprocess, tempfile, time

from run import BASE, MPI_ENV, REPO, cpu_name, run

HERE = os.path.dirname(os.path.abspath(__file__))
WAVY = open(os.path.join(REPO, "prm", "wavy_jfo.prm")).read()
FIELDS_ON = "subsection Output\n  set Write fields = true\nend\n"


def cases(quick):
    """(name, keyword arguments of run()) of one round; the meshes of issue 13 or, quick, a
    sixteenth of them."""
    s = 4 if quick else 1
    tilted_ff = dict(k=2, nr=128 // s, nt=2048 // s, solver="auto")
    tilted_jfo_mesh = dict(k=2, nr=256 // s, nt=1024 // s, solver="auto")
    wavy_mesh = dict(k=2, nr=64 // s, nt=4096 // s, solver="auto", base=WAVY)
    # one rank takes the node's cores as threads (deal.II's rule, applications/main.cc); the run
    # held to one thread shows what two ranks gain over one rank's one core (reported)
    one_thread = dict(MPI_ENV, DEAL_II_NUM_THREADS="1")
    return [("full film", tilted_ff),
            ("full film, 2 ranks", dict(tilted_ff, ranks=2)),
            ("full film, one thread", dict(tilted_ff, env=one_thread)),
            ("full film, fields", dict(tilted_ff, extra=FIELDS_ON)),
            ("full film, JFO mesh", tilted_jfo_mesh),
            ("JFO", dict(tilted_jfo_mesh, cavitation="jfo")),
            ("JFO, 2 ranks", dict(tilted_jfo_mesh, cavitation="jfo", ranks=2)),
            ("JFO, one thread", dict(tilted_jfo_mesh, cavitation="jfo", env=one_thread)),
            ("wavy full film", wavy_mesh),
            ("wavy JFO", dict(wavy_mesh, cavitation="jfo"))]


def run_bare(sealfe, work):
    """`sealfe solve` without a parameter file (the default seal), in an empty directory."""
    d = tempfile.mkdtemp(dir=work)
    t = time.perf_counter()
    r = subprocess.run([sealfe, "solve"], cwd=d, capture_output=True, text=True, env=MPI_ENV)
    wall = time.perf_counter() - t
    shutil.rmtree(d, ignore_errors=True)
    return {"process_wall": round(wall, 3)} if r.returncode == 0 else {"error": r.stderr[-300:]}


def run_table(sealfe, work):
    """`sealfe table prm/table.prm`: its points per second over the sweep."""
    d = tempfile.mkdtemp(dir=work)
    prm = open(os.path.join(REPO, "prm", "table.prm")).read()
    path = os.path.join(d, "table.prm")
    open(path, "w").write(prm + f"\nset Output directory = {d}/out\n")
    t = time.perf_counter()
    r = subprocess.run([sealfe, "table", path], capture_output=True, text=True, env=MPI_ENV)
    wall = time.perf_counter() - t
    if r.returncode:
        return {"error": r.stderr[-300:]}
    s = json.load(open(os.path.join(d, "out", "summary.json")))
    shutil.rmtree(d, ignore_errors=True)
    return {"process_wall": round(wall, 3), "inprocess": s["wall_time"],
            "points": s["points_done"], "sweep_time": s["sweep_wall_time"],
            "points_per_second": s["points_done"] / s["sweep_wall_time"]}


def spread(values):
    """median, min, max of a list (None where empty)"""
    return (statistics.median(values), min(values), max(values)) if values else (None,) * 3


def summarise(rows, rounds):
    """One row per goal: the measured median and range over the rounds, the target, met."""
    by = {(r["round"], r["case"]): r for r in rows if "error" not in r}
    series = lambda case, key="process_wall": [by[(i, case)][key] for i in range(rounds)
                                               if (i, case) in by]

    def ratio(num, den, key="process_wall"):
        return [by[(i, num)][key] / by[(i, den)][key] for i in range(rounds)
                if (i, num) in by and (i, den) in by]

    def force_diff(a, b):
        return [abs(by[(i, a)]["force_z"] / by[(i, b)]["force_z"] - 1) for i in range(rounds)
                if (i, a) in by and (i, b) in by]

    fields_share = [r["output_time"] / (r["inprocess"] - r["output_time"])
                    for r in rows if r["case"] == "full film, fields" and "output_time" in r]
    goals = [
        ("full film, one rank [s]", "full film", series("full film"), "<", 4.0),
        ("full film: 2 ranks / 1 rank speed-up", "full film", ratio("full film", "full film, 2 ranks"), ">=", 1.6),
        ("full film, one rank of one thread [s]", "full film", series("full film, one thread"), "",
         None),
        ("full film: 2 ranks / 1 rank of one thread", "full film",
         ratio("full film, one thread", "full film, 2 ranks"), "", None),
        ("full film: 2 ranks' force_z, relative difference", "full film", force_diff("full film, 2 ranks",
                                                                         "full film"), "<=", 1e-10),
        ("fields: output / rest of the run", "full film", fields_share, "<=", 0.2),
        ("JFO / full film, tilted", "JFO", ratio("JFO", "full film, JFO mesh"), "<=", 3.0),
        ("JFO / full film, tilted, in-process", "JFO",
         ratio("JFO", "full film, JFO mesh", "inprocess"), "<=", 3.0),
        ("JFO / full film, wavy", "wavy JFO", ratio("wavy JFO", "wavy full film"), "<=", 3.0),
        ("JFO / full film, wavy, in-process", "wavy JFO",
         ratio("wavy JFO", "wavy full film", "inprocess"), "<=", 3.0),
        ("JFO: 2 ranks / 1 rank speed-up", "JFO", ratio("JFO", "JFO, 2 ranks"), ">=", 1.6),
        ("JFO, one rank of one thread [s]", "JFO", series("JFO, one thread"), "", None),
        ("JFO: 2 ranks / 1 rank of one thread", "JFO", ratio("JFO, one thread", "JFO, 2 ranks"), "",
         None),
        ("JFO: 2 ranks' force_z, relative difference", "JFO", force_diff("JFO, 2 ranks", "JFO"), "<=",
         1e-10),
        ("bare sealfe solve [s]", "bare solve", series("bare solve"), "<", 0.3),
        ("table: points per second", "table", series("table", "points_per_second"), "", None),
    ]
    out = []
    for name, case, values, relation, target in goals:
        median, lo, hi = spread(values)
        met = ""
        if median is not None and target is not None:
            met = {"<": median < target, "<=": median <= target, ">=": median >= target}[relation]
            met = "yes" if met else "no"
        dofs = next((r.get("dofs") for r in rows if r["case"] == case and "dofs" in r), None)
        out.append({"goal": name, "dofs": dofs, "median": median, "min": lo, "max": hi, "runs": len(values),
                    "target": f"{relation} {target}" if target is not None else "reported",
                    "met (median)": met})
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    # the bare run starts in an empty directory: a relative path would not be found from there
    a.sealfe = os.path.abspath(a.sealfe)
    rounds = 1 if a.quick else a.rounds
    work = tempfile.mkdtemp(prefix="sealfe-goals-")
    rows = []
    for i in range(rounds):
        for name, kwargs in cases(a.quick):
            r = run(a.sealfe, work, **kwargs)
            r.update(round=i, case=name)
            rows.append(r)
            print(f"round {i}: {name}: {r.get('process_wall')} s"
                  + (f" ERROR {r['error']}" if "error" in r else ""), flush=True)
        for name, fn in (("bare solve", run_bare), ("table", run_table)):
            r = dict(fn(a.sealfe, work), round=i, case=name)
            rows.append(r)
            print(f"round {i}: {name}: {r.get('process_wall')} s", flush=True)
    shutil.rmtree(work, ignore_errors=True)
    cpu = cpu_name()
    for r in rows:
        r["cpu"] = cpu
        r["quick"] = a.quick
    summary = summarise(rows, rounds)
    # one file each, written whole; a quick run only prints (the full run's files stay)
    for path, table in () if a.quick else (("goals.csv", rows), ("goals_summary.csv", summary)):
        keys = list(dict.fromkeys(k for r in table for k in r))
        with open(os.path.join(HERE, path), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(table)
    print(f"\n{cpu}, {rounds} round(s)" + (" (quick: not issue 13's meshes)" if a.quick else ""))
    print("| goal | dofs | median | range | target | met |\n|---|---|---|---|---|---|")
    g = lambda v: "" if v is None else f"{v:.3g}"
    for s in summary:
        print(f"| {s['goal']} | {s['dofs'] or ''} | {g(s['median'])} | {g(s['min'])}-{g(s['max'])} | {s['target']} | "
              f"{s['met (median)']} |")


if __name__ == "__main__":
    main()
