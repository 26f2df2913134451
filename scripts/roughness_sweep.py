#!/usr/bin/env python3
"""Load and leakage of the default seal against h_min/sigma, with and without Patir-Cheng flow
factors (GW/CEB contact on in both), by running `sealfe solve`. Writes a CSV and a PNG.

usage: /usr/bin/python3 scripts/roughness_sweep.py [build/sealfe] [doc/roughness_sweep]
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

sealfe = sys.argv[1] if len(sys.argv) > 1 else "build/sealfe"
stem = sys.argv[2] if len(sys.argv) > 2 else "doc/roughness_sweep"
sigma = 5e-7
rows = []
with tempfile.TemporaryDirectory() as work:
    for model in ["none", "patir-cheng"]:
        for H in [0.5, 0.75, 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8]:
            out = os.path.join(work, "out")
            prm = os.path.join(work, "case.prm")
            # a smooth film cannot touch down: start the smooth curve where h_min > 0
            with open(prm, "w") as f:
                f.write(f"""set Output directory = {out}
subsection Geometry
  set Clearance = {H * sigma}
end
subsection Roughness
  set Model = {model}
  set Composite roughness = {sigma}
end
subsection Contact
  set Model = gw-ceb
end
subsection Discretization
  set Error estimate = false
end
subsection Output
  set Write fields = false
end
""")
            r = subprocess.run([sealfe, "solve", prm], capture_output=True, text=True)
            if r.returncode != 0:
                print(model, H, r.stderr.strip())
                continue
            s = json.load(open(os.path.join(out, "summary.json")))
            rows.append({"flow_factors": model, "h_min_over_sigma": H,
                         "force_z_N": s["force_z"], "contact_force_N": s["contact_force"],
                         "leakage_m3_per_s": s["leakage_inner"]})
with open(stem + ".csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
for model, style in [("none", "o--"), ("patir-cheng", "s-")]:
    d = [r for r in rows if r["flow_factors"] == model]
    H = [r["h_min_over_sigma"] for r in d]
    a.semilogy(H, [r["force_z_N"] for r in d], style, label=f"total, flow factors: {model}")
    b.semilogy(H, [r["leakage_m3_per_s"] for r in d], style, label=f"flow factors: {model}")
d = [r for r in rows if r["flow_factors"] == "patir-cheng"]
a.semilogy([r["h_min_over_sigma"] for r in d], [max(r["contact_force_N"], 1e-3) for r in d],
           "^:", label="asperity contact part")
a.set_xlabel("h_min / sigma")
a.set_ylabel("opening force (N)")
a.legend()
b.set_xlabel("h_min / sigma")
b.set_ylabel("leakage (m^3/s)")
b.legend()
fig.suptitle("Default seal, sigma = 0.5 um, GW/CEB contact (Green (2002) Table 1 asperities)")
fig.tight_layout()
fig.savefig(stem + ".png", dpi=100)
print("wrote", stem + ".csv", stem + ".png")
