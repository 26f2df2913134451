#!/usr/bin/env python3
"""Runs the paper reproductions in benchmarks/<paper>/ and prints sealfe's numbers next to the
papers'.

    benchmarks/run_papers.py [path/to/sealfe] [paper ...]

paper: wileman_green, varney_green_2017, etsion_1977, fleming_1977 (default: all). The binary
defaults to build/sealfe. Each run includes the paper's prm, overrides the Output directory (a
temporary directory) and, for the other rows of a table, one or two entries. About 40 s in all
(Wileman & Green's Table 1 is 38 runs of ~1 s). Python 3 standard library only.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(binary, command, prm, overrides, workdir, name):
    """sealfe <command> on `prm` with `overrides` (prm text); returns (summary, output dir)."""
    out = os.path.join(workdir, name)
    case = os.path.join(workdir, name + ".prm")
    with open(case, "w") as f:
        f.write("include %s\n%s\nset Output directory = %s\n" % (prm, overrides, out))
    r = subprocess.run([binary, command, case], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (name, r.stderr.strip()))
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f), out


def rel(a, b):
    return (a - b) / abs(b)


# ---- Wileman & Green, Table 1 ------------------------------------------------------------------
# variable, value, then the printed stable omega2 range for c2 = 0.5 and c2 = 3 (rad/s).
WILEMAN_GREEN_TABLE_1 = [
    ("I1", 4.0e-4, -14011.8, 9481.8, -1971.2, 3473.5),
    ("I1", 1.2e-3, -9628.3, 4460.3, -3289.4, 2554.8),
    ("I2", 4.0e-4, -10629.2, 4174.1, -4149.5, 2704.6),
    ("I2", 1.2e-3, -11003.6, 6411.0, -1964.6, 2860.1),
    ("ks1", 100, -10798.4, 5825.5, -2692.3, 2554.6),
    ("ks1", 700, -11003.8, 6203.6, -2930.9, 2985.7),
    ("ks2", 100, -10900.7, 5994.9, -2602.4, 2445.8),
    ("ks2", 700, -10903.0, 6051.0, -3014.2, 3091.1),
    ("ds1", 0, -10216.9, 274.3, -2561.9, 242.9),
    ("ds1", 0.48, -11568.6, 7429.1, -3144.0, 5722.8),
    ("ds2", 0, -10916.2, 860.4, -14277.6, 9479.3),
    ("ds2", 0.48, -10887.6, 5435.8, -2628.2, 1466.9),
    ("po-pi", 5e5, -9125.8, 4644.2, -2438.7, 3033.8),
    ("po-pi", 1.5e6, -12341.8, 7262.9, -2985.2, 2693.8),
    ("beta*", 1.56e-3, -10069.6, 4924.8, -2802.6, 2813.5),
    ("beta*", 4.69e-3, -11306.4, 6796.6, -2760.5, 2790.0),
    ("C0", 5e-6, -12754.0, 6727.4, -3173.3, 2652.6),
    ("C0", 1.5e-5, -11019.0, 6984.0, -2545.6, 2913.1),
    ("reference", None, -10901.8, 6024.2, -2816.1, 2776.3),
]


def ring(name, entries):
    body = "".join("    set %s = %r\n" % (k, v) for k, v in entries.items())
    return "subsection Seal dynamics\n  subsection %s\n%s  end\nend\n" % (name, body)


def wileman_green_overrides(variable, value, c2):
    """prm text for one row of Table 1. The inertia ratios c_n = I_n/J_n are held (J follows I);
    the support turns with its shaft (rotating damping = support damping); the clearance rows
    hold beta* ro / C0 = 12.52, as the paper did."""
    text = ring("Stator ring", {"Polar inertia": 8e-4 / c2})
    if variable == "I1":
        text += ring("Rotor ring", {"Transverse inertia": value, "Polar inertia": value / 0.5})
    elif variable == "I2":
        text += ring("Stator ring", {"Transverse inertia": value, "Polar inertia": value / c2})
    elif variable == "ks1":
        text += ring("Rotor ring", {"Support stiffness": value})
    elif variable == "ks2":
        text += ring("Stator ring", {"Support stiffness": value})
    elif variable == "ds1":
        text += ring("Rotor ring", {"Support damping": value, "Rotating damping": value})
    elif variable == "ds2":
        text += ring("Stator ring", {"Support damping": value, "Rotating damping": value})
    elif variable == "po-pi":
        text += "subsection Operating conditions\n  set Outer pressure = %r\nend\n" % value
    elif variable == "beta*":
        text += "subsection Geometry\n  set Coning = %r\nend\n" % value
    elif variable == "C0":
        text += ("subsection Geometry\n  set Clearance = %r\n  set Coning = %r\nend\n" %
                 (value, 3.13e-3 * value / 1e-5))
    return text


def wileman_green(binary, workdir):
    prm = os.path.join(HERE, "wileman_green", "table1.prm")
    print("Wileman & Green, Table 1: stable range of omega2 (rad/s), omega1 = -2000 rad/s, FMRR,")
    print("level 0 film (Green & Etsion). Paper min / max, sealfe min / max, largest deviation.")
    print("%-10s %8s | %-20s %-20s | %-20s %-20s | %s" %
          ("variable", "value", "c2=0.5 paper", "c2=0.5 sealfe", "c2=3 paper", "c2=3 sealfe",
           "dev"))
    worst = 0
    for variable, value, *printed in WILEMAN_GREEN_TABLE_1:
        cells, dev = [], 0
        for k, c2 in enumerate((0.5, 3.0)):
            s, _ = run(binary, "stability", prm, wileman_green_overrides(variable, value, c2),
                       workdir, "wg_%s_%s_%g" % (variable.replace("*", ""), value, c2))
            lo, hi = s["stable_range"]
            p_lo, p_hi = printed[2 * k], printed[2 * k + 1]
            dev = max(dev, abs(rel(lo, p_lo)), abs(rel(hi, p_hi)))
            cells += ["%9.1f / %8.1f" % (p_lo, p_hi), "%9.1f / %8.1f" % (lo, hi)]
        worst = max(worst, dev)
        print("%-10s %8s | %-20s %-20s | %-20s %-20s | %.3f%%" %
              (variable, "" if value is None else "%g" % value, *cells, 100 * dev))
    print("largest deviation %.3f%% (doc/dynamics.md: 0.13%%)\n" % (100 * worst))


# ---- Varney & Green (2017) ---------------------------------------------------------------------
def peak(csv_file, column):
    with open(csv_file) as f:
        lines = f.readlines()
        header = [h.split(" [")[0] for h in lines[0].strip().split(",")]  # doc/csv.md
        i, j = header.index("swept_speed"), header.index(column)
        rows = [line.strip().split(",") for line in lines[1:] if line.strip()]
    best = max(rows, key=lambda r: float(r[j]))
    return float(best[i]), float(best[j])


def varney_green_2017(binary, workdir):
    prm = os.path.join(HERE, "varney_green_2017", "fig6.prm")
    print("Varney & Green (2017): rotor-tilt critical speed of the thick rotor (delta = 2),")
    print("chi = 0.5 mrad, level 0 film. Peak of response.csv rotor_tilt on a 1 rad/s grid.")
    cases = [
        ("K_r = 1e5, I_tr/I_ts = 50 (Fig. 6)", "", 990.0),
        ("K_r = 1e5, I_tr/I_ts = 6.48", ring("Stator ring", {"Transverse inertia": 0.2 / 6.48}),
         877.3),
    ]
    print("%-38s %12s %12s %8s" % ("case", "paper", "sealfe", "dev"))
    for k, (name, text, paper) in enumerate(cases):
        s, out = run(binary, "response", prm, text, workdir, "vg_%d" % k)
        speed, _ = peak(os.path.join(out, "response.csv"), "rotor_tilt")
        print("%-38s %12.1f %12.1f %7.1f%%" % (name, paper, speed, 100 * rel(speed, paper)))
    # Table 2 as printed: K_r = 5e5 puts the rotor's critical speed at sqrt(K_r/(I_tr - I_pr)).
    text = (ring("Rotor ring", {"Support stiffness": 5e5}) +
            "subsection Forced response\n  set Speed from = 10\n  set Speed to = 5000\n"
            "  set Speed points = 500\nend\n")
    s, out = run(binary, "response", prm, text, workdir, "vg_printed")
    speed, _ = peak(os.path.join(out, "response.csv"), "rotor_tilt")
    print("%-38s %12.1f %12.1f   (printed K_r: the paper's 990 needs K_r = 1e5)" %
          ("K_r = 5e5 as printed, I_tr/I_ts = 50", 990.0, speed))
    print("  rotor_critical_speed %.1f rad/s, peak relative tilt %.3e rad at %.0f rad/s,"
          % (s["rotor_critical_speed"], s["peak_relative_tilt"],
             s["speed_at_peak_relative_tilt"]))
    print("  face contact (relative tilt > C0/ri) over %s rad/s\n" % s["contact_speed_ranges"])


# ---- Etsion (1977), Table I ----------------------------------------------------------------------
# row, Ri, epsilon, printed Fbar, Mbar_x, Mbar_z (rows 1 and 27 carry misprints, doc/narrow_seal.md)
ETSION_TABLE_I = [
    (1, 0.80, 0.1, 0.110e-03, 0.887e-05, 0.773e-04),
    (5, 0.80, 0.5, 0.850e-03, 0.345e-03, 0.537e-03),
    (9, 0.80, 0.9, 0.876e-02, 0.645e-02, 0.355e-02),
    (13, 0.85, 0.3, 0.170e-03, 0.435e-04, 0.118e-03),
    (25, 0.90, 0.5, 0.125e-03, 0.566e-04, 0.824e-04),
    (27, 0.90, 0.7, 0.349e-03, 0.215e-03, 0.189e-03),
    (29, 0.90, 0.9, 0.192e-02, 0.157e-02, 0.736e-03),
    (35, 0.92, 0.5, 0.664e-04, 0.306e-04, 0.439e-04),
]


def etsion_1977(binary, workdir):
    prm = os.path.join(HERE, "etsion_1977", "table_I.prm")
    ro, C, mu, omega = 0.04, 1e-6, 1e-3, 1000.0
    scale = 6 * mu * omega * (ro / C) ** 2 * ro ** 2
    print("Etsion (1977), Table I (half-Sommerfeld): printed / sealfe (narrow-seal film, level 0)")
    print("%4s %5s %4s | %-22s | %-22s | %-22s" % ("row", "Ri", "eps", "Fbar", "Mbar_x", "Mbar_z"))
    for row, Ri, eps, *printed in ETSION_TABLE_I:
        text = ("subsection Geometry\n  set Inner radius = %r\n  set Tilt = %r\nend\n" %
                (Ri * ro, eps * C / ro))
        s, _ = run(binary, "solve", prm, text, workdir, "etsion_%d" % row)
        got = [s["force_z"] / scale, s["moment_restoring"] / (scale * ro),
               s["moment_transverse"] / (scale * ro)]
        print("%4d %5.2f %4.1f | %s" % (row, Ri, eps, " | ".join(
            "%.3E / %.4E" % (p, g) for p, g in zip(printed, got))))
    print("rows 1 (Mbar_x 0.889E-05) and 27 (Fbar 0.339E-03) are misprinted in the paper;")
    print("all 80 rows: tests/validation/etsion_table_models.cc, doc/narrow_seal.md\n")


# ---- Fleming (1977) -------------------------------------------------------------------------------
def fleming_1977(binary, workdir):
    prm = os.path.join(HERE, "fleming_1977", "stepped_seal.prm")
    s, _ = run(binary, "annular", prm, "", workdir, "fleming")
    straight = s["straight_seal"]["stiffness_dimensionless"]
    print("Fleming (1977): stepped seal, max K/M, gamma <= 0.8, Lambda = %.3f" % s["lambda"])
    print("%-40s %10s %10s" % ("", "paper", "sealfe"))
    for name, paper, value in [
        ("straight seal Kbar (Fig. 6)", "0.11", "%.4f" % straight),
        ("clearance ratio H (Fig. 3)", "1.59", "%.4f" % s["clearance_ratio"]),
        ("step position gamma (Fig. 4)", "0.70", "%.4f" % s["step_ratio"]),
        ("stepped seal Kbar (Fig. 6)", "0.29", "%.4f" % s["stiffness_dimensionless"]),
        ("stiffness over straight", "nearly 3", "%.2f" % (s["stiffness_dimensionless"] / straight)),
    ]:
        print("%-40s %10s %10s" % (name, paper, value))
    print("the Lambda sweep (Figs. 2-8): sealfe annular prm/annular.prm, doc/annular_seals.md\n")


PAPERS = {"wileman_green": wileman_green, "varney_green_2017": varney_green_2017,
          "etsion_1977": etsion_1977, "fleming_1977": fleming_1977}


def main(argv):
    binary = os.path.join(ROOT, "build", "sealfe")
    if argv and not argv[0] in PAPERS:
        binary = argv.pop(0)
    binary = os.path.abspath(binary)
    if not os.access(binary, os.X_OK):
        sys.exit("run_papers.py: no executable sealfe at %s" % binary)
    papers = argv or list(PAPERS)
    with tempfile.TemporaryDirectory(prefix="sealfe_papers_") as workdir:
        for p in papers:
            if p not in PAPERS:
                sys.exit("run_papers.py: unknown paper '%s' (%s)" % (p, ", ".join(PAPERS)))
            PAPERS[p](binary, workdir)


if __name__ == "__main__":
    main(sys.argv[1:])
