#!/usr/bin/env python3
"""Large runout: the nonlinear steady whirl of the FMS on Varney & Green's flexible rotor against
its linear response, and the onset of face contact.

    benchmarks/varney_green_2017/nonlinear_departure.py [--sealfe build/sealfe] [--out DIR]

For each shaft speed and dynamic misalignment chi, `sealfe equilibrium` solves the steady state
of the transient's nonlinear equations (Green 2002 Eq. 26 with the flexible rotor of Varney &
Green 2017 Eq. 5-6, asperity contact GW/CEB, level-0 film with half-Sommerfeld) in the frame
turning with the shaft. The linear response is the same steady state at chi = 1e-7 rad scaled by
chi/1e-7 (tests/validation/green2002_linearisation.cc checks that this small-chi steady state
equals `sealfe response`'s linear forced response). Writes into DIR (default
benchmarks/varney_green_2017/results): nonlinear_departure.csv (one row per speed and chi) and
nonlinear_departure.png. Python 3 standard library + matplotlib; about a minute.

Seal: Varney & Green 2017 Table 1 (C0 = 1 um, beta* = 1 mrad, 400 kPa), stator of prm/response.prm
(I_ts = 4e-3 kg m^2, K_s = 363.9 N m/rad, D_s = 0.22 N m s/rad), Table 2's thick rotor with
K_r = 1e5 N m/rad (critical speed 990 rad/s, README), balance ratio 0.87 (the axial balance then
sits at ~1 um at 990 rad/s; Varney & Green fix the clearance instead of solving it).
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RI = 0.0355
C0 = 1e-6

CASE = """
subsection Geometry
  set Inner radius = 0.0355
  set Outer radius = 0.0408
  set Clearance    = 1e-6
  set Coning       = 1e-3
end
subsection Operating conditions
  set Viscosity      = 1.2e-3
  set Inner pressure = 0
  set Outer pressure = 4e5
  set Rotor speed    = {speed}
end
subsection Thermal coning
  set Model = none
end
subsection Closing force
  set Balance ratio = 0.87
  set Spring force  = 0
end
subsection Stator ring
  set Transverse inertia = 4e-3
  set Angular stiffness  = 363.9
  set Angular damping    = 0.22
end
subsection Rotor runout
  set Tilt = 0
end
subsection Rotor ring
  set Model                = flexible
  set Transverse inertia   = 0.2
  set Polar inertia        = 0.1
  set Angular stiffness    = 1e5
  set Angular damping      = 20
  set Rotating damping     = 1
  set Dynamic misalignment = {chi}
end
"""


def steady(sealfe, runs, speed, chi):
    name = f"w{speed:g}_chi{chi:g}"
    d = os.path.join(runs, name)
    os.makedirs(d, exist_ok=True)
    prm = os.path.join(d, "case.prm")
    with open(prm, "w") as f:
        f.write(f"set Output directory = {os.path.join(d, 'out')}\n")
        f.write(CASE.format(speed=speed, chi=chi))
    r = subprocess.run([sealfe, "equilibrium", prm], capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr.strip().splitlines()[-1] if r.stderr else "failed"
    with open(os.path.join(d, "out", "summary.json")) as f:
        return json.load(f), ""


def plot(rows, chis, out):
    fig, ax = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for chi in chis:
        r = [x for x in rows if x["dynamic_misalignment [rad]"] == chi]
        ws = [x["rotor_speed [rad/s]"] for x in r]
        line = ax[0].plot(ws, [x["relative_tilt [rad]"] * 1e6 for x in r],
                          label=f"nonlinear, chi = {chi * 1e3:g} mrad")[0]
        ax[0].plot(ws, [x["relative_tilt_linear [rad]"] * 1e6 for x in r], "--",
                   color=line.get_color(), label=f"linear, chi = {chi * 1e3:g} mrad")
        ax[1].plot(ws, [x["clearance [m]"] * 1e6 for x in r], color=line.get_color(),
                   label=f"chi = {chi * 1e3:g} mrad")
    ax[0].axhline(C0 / RI * 1e6, color="k", lw=0.8, ls=":", label="C0 / ri (contact, linear)")
    ax[0].set_ylabel("relative tilt γ* [µrad]")
    ax[0].legend(fontsize=8)
    ax[0].set_title("FMS on a flexible rotor (Varney & Green 2017, K_r = 1e5 N m/rad)\n"
                    "gaps: no steady whirl (fold)", fontsize=10)
    ax[1].set_ylabel("clearance C0 + z [µm]")
    ax[1].set_xlabel("shaft speed ω [rad/s]")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "nonlinear_departure.png"), dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sealfe", default=os.path.join(ROOT, "build", "sealfe"))
    p.add_argument("--out", default=os.path.join(HERE, "results"))
    p.add_argument("--plot-only", action="store_true", help="re-plot the CSV in --out")
    a = p.parse_args()
    chis = [0.1e-3, 0.25e-3, 0.5e-3]
    if a.plot_only:
        with open(os.path.join(a.out, "nonlinear_departure.csv")) as f:
            rows = [{k: (v if k == "note" else float(v)) for k, v in r.items()}
                    for r in csv.DictReader(f)]
        plot(rows, chis, a.out)
        return
    os.makedirs(a.out, exist_ok=True)
    runs = tempfile.mkdtemp(prefix="sealfe_vg_nonlinear_")
    speeds = [500 + 25 * i for i in range(41)]  # 500 ... 1500 rad/s
    small = 1e-7
    rows = []
    for w in speeds:
        lin, err = steady(a.sealfe, runs, w, small)
        if lin is None:
            print(f"{w} rad/s: linear reference failed: {err}")
            continue
        per_chi = lin["relative_tilt"] / small
        for chi in chis:
            s, err = steady(a.sealfe, runs, w, chi)
            row = {
                "rotor_speed [rad/s]": w,
                "dynamic_misalignment [rad]": chi,
                "relative_tilt_linear [rad]": per_chi * chi,
                "relative_tilt [rad]": s["relative_tilt"] if s else float("nan"),
                "departure [-]": (s["relative_tilt"] / (per_chi * chi) - 1) if s else float("nan"),
                "min_film_over_sigma [-]": s["min_film_over_sigma"] if s else float("nan"),
                "contact_force [N]": s["contact_force"] if s else float("nan"),
                "clearance [m]": s["clearance"] if s else float("nan"),
                "note": err,
            }
            rows.append(row)
            print(
                f"{w:6g} rad/s chi {chi:.2e}: relative tilt {row['relative_tilt [rad]']:.3e} "
                f"(linear {row['relative_tilt_linear [rad]']:.3e}, departure "
                f"{row['departure [-]']:+.3f}), contact {row['contact_force [N]']:.3g} N {err}"
            )
    with open(os.path.join(a.out, "nonlinear_departure.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    plot(rows, chis, a.out)
    shutil.rmtree(runs)
    print("wrote", os.path.join(a.out, "nonlinear_departure.csv"), "and .png")


if __name__ == "__main__":
    main()
