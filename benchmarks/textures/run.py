#!/usr/bin/python3
"""JFO against full film on faces that resolve their surface features (issue 16, "Speed").

    /usr/bin/python3 benchmarks/textures/run.py [--repeat 3] [--cases grooves,dimples,fitted]
                                               [--sealfe build/sealfe] [--label after]

Cases (the faces of tests/long/surface_feature_convergence.cc, JfoCostOnResolvedFaces):
  grooves: 12 inward-pumping spiral grooves on the band 33..40 mm of a flat dam 30..40 mm
           (h = 3 um, depth 6 um, alpha = 0.3, groove fraction 0.5, 500 rad/s), 1e5 Pa on both
           circles; aligned built-in mesh, 32 cells per groove x 32 radial, degree 2;
  dimples: 975 dimples (5 rows of 195, r_p = 0.3 mm, S_p = 0.2, depth 4 um) on the dam
           34..40 mm, h = 2 um, 1e5 Pa both sides, 300 rad/s; built-in mesh 1560 x 40 cells
           (8 cells per dimple pitch), degree 1;
  fitted:  the same 975 dimples on the gmsh mesh with every dimple circle a mesh line
           (`Mesh size` 0.15 mm, no refinement), degree 1 (needs gmsh).
Each case runs with `Cavitation/Model = none` (full film) and `jfo` on the same mesh,
`Error estimate = false`, `Write fields = false`, one rank. Records dofs, the in-process time
(summary.json `wall_time`) and its stages (`stage_wall_time`), the whole-process time, the
JFO/full-film ratios, Newton steps, active-set rounds, factorisations (last level, band rounds,
coarse levels), the force, the cavitated fraction and the mass balance. Each run `--repeat`
times (minimum kept); the load average (`uptime`) before each case is recorded.
Writes benchmarks/textures/textures.csv (rows of earlier labels kept, so that a "before" and an
"after" binary can share the file) and textures.png.
"""
import argparse, csv, json, os, shutil, subprocess, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))

GROOVES = """
subsection Geometry
  set Inner radius = 0.030
  set Outer radius = 0.040
  set Clearance = 3e-6
  set Coning = 0
  subsection Surface features
    subsection Spiral grooves
      set Number = 12
      set Depth = 6e-6
      set Spiral angle = 0.3
      set Groove fraction = 0.5
      set Inner radius = 0.033
      set Pumping direction = inward
    end
  end
end
subsection Operating conditions
  set Inner pressure = 1e5
  set Outer pressure = 1e5
  set Reference pressure = 1e5
  set Rotor speed = 500
  set Viscosity = 1.2e-3
end
subsection Discretization
  set Radial cells = 32
  set Circumferential cells = 384
  set Polynomial degree = 2
  set Radial grading = false
  set Align with features = true
end
"""

DIMPLES = """
subsection Geometry
  set Inner radius = 0.034
  set Outer radius = 0.040
  set Clearance = 2e-6
  set Coning = 0
  subsection Surface features
    subsection Dimples
      set Area density = 0.2
      set Radius = 3e-4
      set Depth = 4e-6
      set Pattern = regular
    end
  end
end
subsection Operating conditions
  set Inner pressure = 1e5
  set Outer pressure = 1e5
  set Reference pressure = 1e5
  set Rotor speed = 300
end
subsection Discretization
  set Radial cells = 40
  set Circumferential cells = 1560
  set Polynomial degree = 1
  set Radial grading = false
end
"""

FITTED = DIMPLES + """
subsection Discretization
  set Mesh size = 0.15e-3
  set Global refinements = 0
end
"""

CASES = {"grooves": ("12 spiral grooves", GROOVES), "dimples": ("975 dimples, built-in mesh", DIMPLES),
         "fitted": ("975 dimples, fitted mesh", FITTED)}


def load_average():
    return float(open("/proc/loadavg").read().split()[0])


def run(sealfe, work, base, model):
    out = tempfile.mkdtemp(dir=work)
    prm = base + f"""
set Output directory = {out}
subsection Discretization
  set Error estimate = false
end
subsection Cavitation
  set Model = {model}
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
        raise RuntimeError(r.stderr.strip()[-500:])
    s = json.load(open(os.path.join(out, "summary.json")))
    shutil.rmtree(out, ignore_errors=True)
    os.remove(path)
    st = s.get("stage_wall_time", {})
    ls = s.get("linear_solver", {})
    c = s.get("cavitation", {})
    return {"dofs": s["dofs"], "process_wall": round(wall, 3), "inprocess": s.get("wall_time"),
            "stages": st, "factorizations": ls.get("factorizations"),
            "newton_steps": c.get("newton_steps"), "active_set_rounds": c.get("active_set_rounds"),
            "band_factorizations": c.get("band_factorizations"),
            "coarse_iterations": c.get("coarse_level_iterations"),
            "coarse_factorizations": c.get("coarse_level_factorizations"),
            "low_rank_updates": c.get("low_rank_updates"),
            "workspace_retries": ls.get("workspace_retries"),
            "band_workspace_retries": c.get("band_workspace_retries"),
            "coarse_workspace_retries": c.get("coarse_level_workspace_retries"),
            "force_z": s["force_z"], "cavitated_fraction": s.get("cavitated_fraction"),
            "mass_imbalance": s.get("mass_balance_residual"), "moment_x": s.get("moment_x"),
            "nonlinear_residual": c.get("final_residual")}


def best_of(n, *args):
    runs = [run(*args) for _ in range(n)]
    best = min(runs, key=lambda r: r["inprocess"])
    best["process_wall"] = min(r["process_wall"] for r in runs)
    return best


def read_rows(path):
    rows = []
    if os.path.exists(path):
        for r in csv.DictReader(open(path)):
            for key, v in list(r.items()):
                try:
                    r[key] = int(v)
                except ValueError:
                    try:
                        r[key] = float(v)
                    except ValueError:
                        pass
            rows.append(r)
    return rows


STAGES = ("setup", "assemble", "cavitation", "jfo coarse levels", "linear solver setup",
          "jfo assembly", "jfo cell matrices", "loads")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("--cases", default="grooves,dimples,fitted")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--label", default="after", help="tag of the rows (e.g. before, after)")
    ap.add_argument("--plot-only", action="store_true")
    a = ap.parse_args()
    path = os.path.join(HERE, "textures.csv")
    rows = read_rows(path)
    if not a.plot_only:
        work = tempfile.mkdtemp(prefix="sealfe-textures-")
        new = []
        for case in a.cases.split(","):
            name, base = CASES[case]
            load = load_average()
            full = best_of(a.repeat, a.sealfe, work, base, "none")
            jfo = best_of(a.repeat, a.sealfe, work, base, "jfo")
            r = {"label": a.label, "case": case, "face": name, "load_average": load,
                 "load_average_after": load_average(), "dofs": jfo["dofs"],
                 "full_film_inprocess": full["inprocess"], "full_film_process": full["process_wall"],
                 "jfo_inprocess": jfo["inprocess"], "jfo_process": jfo["process_wall"],
                 "ratio_inprocess": round(jfo["inprocess"] / full["inprocess"], 3),
                 "ratio_process": round(jfo["process_wall"] / full["process_wall"], 3)}
            for key in ("newton_steps", "active_set_rounds", "factorizations", "band_factorizations",
                        "coarse_iterations", "coarse_factorizations", "low_rank_updates",
                        "workspace_retries", "band_workspace_retries",
                        "coarse_workspace_retries", "force_z",
                        "cavitated_fraction", "mass_imbalance"):
                r[key] = jfo[key]
            r["full_film_force_z"] = full["force_z"]
            for stage in STAGES:
                r["jfo " + stage if not stage.startswith("jfo") else stage] = \
                    round(jfo["stages"].get(stage, 0), 4)
            print(json.dumps(r), flush=True)
            new.append(r)
        shutil.rmtree(work, ignore_errors=True)
        done = {(r["label"], r["case"]) for r in new}
        rows = [r for r in rows if (r["label"], r["case"]) not in done] + new
        keys = list(dict.fromkeys(k for r in rows for k in r))
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)
    plot(rows)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    labels = sorted(dict.fromkeys(r["label"] for r in rows), key=lambda l: (l != "before", l))
    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    width = 0.8 / (len(labels) + 1)
    for j, label in enumerate(labels):
        for i, case in enumerate(cases):
            sel = [r for r in rows if r["label"] == label and r["case"] == case]
            if not sel:
                continue
            r = sel[0]
            x = i + (j - len(labels) / 2) * width
            # JFO in-process time split into its stages; the full film beside it
            bottom = 0
            parts = (("jfo setup", "tab:olive"), ("jfo coarse levels", "tab:orange"), ("jfo linear solver setup", "tab:red"),
                     ("jfo assembly", "tab:purple"), ("jfo cell matrices", "tab:pink"))
            for key, colour in parts:
                v = r.get(key) or 0
                axes[0].bar(x, v, width, bottom=bottom, color=colour,
                            label=key[4:] + (" (mesh, dofs; gmsh)" if key == "jfo setup" else "")
                            if i == 0 and j == 0 else None)
                bottom += v
            axes[0].bar(x, r["jfo_inprocess"] - bottom, width, bottom=bottom, color="tab:gray",
                        label="rest of JFO" if i == 0 and j == 0 else None)
            axes[0].plot([x - width / 2, x + width / 2], [r["full_film_inprocess"]] * 2, "k-", lw=2,
                         label="full film" if i == 0 and j == 0 else None)
            axes[0].text(x, r["jfo_inprocess"], label, ha="center", va="bottom", fontsize=7)
            axes[1].bar(x, r["ratio_inprocess"], width, color=f"C{j}",
                        label=f"{label}, in-process" if i == 0 else None)
            axes[1].plot(x, r["ratio_process"], "kx", label="whole process" if i == 0 and j == 0 else None)
            axes[1].text(x, r["ratio_inprocess"], f"{r['ratio_inprocess']:.1f}", ha="center",
                         va="bottom", fontsize=7)
    names = []
    for case in cases:
        r = [r for r in rows if r["case"] == case][-1]
        names.append(f"{r['face']}\n{int(r['dofs'])} dofs")
    for ax in axes:
        ax.set_xticks(range(len(cases)))
        ax.set_xticklabels(names, fontsize=8)
    axes[0].set_ylabel("in-process wall time [s]")
    axes[0].set_title("JFO time by stage (bars) against the full film (black line)", fontsize=9)
    axes[0].legend(fontsize=7)
    axes[1].axhline(3, color="k", ls=":", lw=1)
    axes[1].set_ylabel("JFO / full film")
    axes[1].set_title("JFO / full-film time on the same mesh (issue 16 target: 3)", fontsize=9)
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "textures.png"), dpi=110)


if __name__ == "__main__":
    main()
