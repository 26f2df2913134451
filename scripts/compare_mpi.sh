#!/usr/bin/env bash
# The same solve on 1 and 2 MPI ranks (JFO also 3) must give the same loads (to 1e-9 relative;
# `auto`, which is direct on one rank and cg-gmg on two, to 1e-10); cg-gmg on 2 and 3 ranks the
# loads of the direct solver on one (1e-9).
# Usage: compare_mpi.sh path/to/sealfe [case ...]   (cases: direct cg-amg cg-gmg auto jfo
# jfo-auto gmg-vs-direct coefficients fitted; default all)
set -euo pipefail
sealfe=$1
shift
cases=${*:-direct cg-amg cg-gmg auto jfo jfo-auto gmg-vs-direct coefficients fitted}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# compare DIR1 DIR2 LABEL [RANKS [TOLERANCE]]: the loads of two summaries (1 and RANKS ranks,
# default 2) agree to TOLERANCE relative (default 1e-9)
compare() {
  python3 - "$1/summary.json" "$2/summary.json" "$3" "${4:-2}" "${5:-1e-9}" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
keys = ["force_z", "moment_x", "moment_y", "moment_restoring", "moment_transverse",
        "leakage_inner", "leakage_outer", "friction_torque", "max_pressure", "min_pressure",
        "cavitated_fraction"]
ranks = int(sys.argv[4])
tolerance = float(sys.argv[5])
assert b["mpi_ranks"] == ranks and a["mpi_ranks"] == 1
worst = 0.0
for k in keys:
    scale = max(abs(a[k]), 1e-300)
    if k.startswith("moment"):
        scale = max(scale, 1e-9 * abs(a["force_z"]) * 0.04)
    if k.startswith("leakage"):
        scale = max(abs(a["leakage_inner"]), abs(a["leakage_outer"]))
    worst = max(worst, abs(a[k] - b[k]) / scale)
print(f"{sys.argv[3]}: max relative difference 1 vs {ranks} ranks = {worst:.2e}")
sys.exit(0 if worst < tolerance else 1)
PY
}
# write_case DIR LINEAR CAVITATION OUTER_PRESSURE: the case file of one run, output in DIR
write_case() {
  cat > "$work/case.prm" <<PRM
set Output directory = $1
subsection Geometry
  set Tilt = 1.2e-5
  set Tilt angle = 0.7
  set Wave amplitude = 2e-7
  set Wave number = 3
end
subsection Operating conditions
  set Inner pressure = 2e4
  set Outer pressure = $4
end
subsection Cavitation
  set Model = $3
end
subsection Discretization
  set Linear solver = $2
  set Radial cells = 8
  set Circumferential cells = 64
  set Global refinements = 1
end
PRM
}
# methods SUMMARY... EXPECTED...: the linear solver each summary names is the expected one
methods() {
  python3 - "$@" <<'PY'
import json, sys
n = len(sys.argv[1:]) // 2
files, expected = sys.argv[1:1 + n], sys.argv[1 + n:]
methods = [json.load(open(f))["linear_solver"]["method"] for f in files]
print(f"linear solver of {len(files)} runs = {methods}")
sys.exit(0 if methods == expected else 1)
PY
}
# bands SUMMARY1 SUMMARY...: the JFO runs on 1, 2, ... ranks all take band rounds of the polish
# (small factorisations around the flipped nodes; this case takes 6 on every rank count)
bands() {
  python3 - "$@" <<'PY'
import json, sys
cavitation = [json.load(open(f))["cavitation"] for f in sys.argv[1:]]
counts = [c["band_factorizations"] for c in cavitation]
print(f"JFO band factorisations on 1, 2, ... ranks = {counts}")
# their MUMPS workspace retries: each band round has its own SparseDirect, which throws after
# max_workspace_retries = 3 (sparse_direct.cc), so more than 3 per band means a miscount
retries = [c["band_workspace_retries"] for c in cavitation]
print(f"JFO band workspace retries on 1, 2, ... ranks = {retries}")
assert all(r <= 3 * n for r, n in zip(retries, counts)), "more than 3 retries per band"
sys.exit(0 if min(counts) > 0 else 1)
PY
}
# full film with the direct solver, CG + AMG and CG + geometric multigrid (8 x 64 cells refined
# once: two levels, so that the 2-rank paths of the level transfer and of the finest level's
# numbering run), and the mass-conserving JFO cavitation (a wavy seal at a low sealed pressure)
# with the direct solver, also on 3 ranks (its coarse levels solved whole on every rank, the
# finest level split unevenly among the coarse grid's trees). `auto` (8448 unknowns) factorises
# on one rank and takes cg-gmg on two (FilmLinearSolver::choose): summary.json must say so, and
# the loads agree to 1e-10 (CG to a relative residual of 1e-12 against the factorisation).
# `jfo-auto`: the JFO case with `auto` on 1, 2 and 3 ranks (the Newton systems factorised on
# every rank count; the full-film start by cg-gmg on several ranks, CG to 1e-12), to 1e-9.
for solver in direct cg-amg cg-gmg auto jfo jfo-auto; do
  case " $cases " in *" $solver "*) ;; *) continue ;; esac
  cavitation=none
  pressure=4e5
  linear=$solver
  ranks="1 2"
  if [ "$solver" = jfo ]; then cavitation=jfo; pressure=5e4; linear=direct; ranks="1 2 3"; fi
  if [ "$solver" = jfo-auto ]; then cavitation=jfo; pressure=5e4; linear=auto; ranks="1 2 3"; fi
  for n in $ranks; do
    write_case "$work/np$n-$solver" "$linear" "$cavitation" "$pressure"
    mpirun -np $n "$sealfe" solve "$work/case.prm" > /dev/null
  done
  if [ "$solver" = auto ]; then
    methods "$work/np1-auto/summary.json" "$work/np2-auto/summary.json" direct cg-gmg
    compare "$work/np1-auto" "$work/np2-auto" auto 2 1e-10
  else
    compare "$work/np1-$solver" "$work/np2-$solver" "$solver"
  fi
  if [ "$ranks" = "1 2 3" ]; then
    compare "$work/np1-$solver" "$work/np3-$solver" "$solver" 3
    bands "$work"/np{1,2,3}-$solver/summary.json
  fi
done
# cg-gmg on 2 and 3 ranks against the direct solver on one (the full film of the cases above):
# the V-cycle's level transfer, line smoother and finest level split among the ranks (3 ranks:
# unevenly among the coarse grid's trees) must change nothing but round-off and the CG stopping
# point. Each load L is linear in p: L(p_cg) - L(p) = z.r with A z = w (the load's adjoint) and
# r = b - A p_cg the residual, |z.r| <= |z||r| <= 1e-12 |z||b| (`Solver tolerance`): a relative
# load error of at most 1e-12 |z||b| / |L(p)|, 1e-9 while |z||b| / |L(p)| <= 1e3 (|L(p)| ~ z.b:
# both z and b are smooth on the film, the adjoints of force, moment and leakage solutions of
# the film operator with a smooth source or boundary data, so their cosine is far from 1e-3).
# KLU's own error is ~1e-16 cond(A), below 1e-11 for cond(A) < 1e5 (16 radial Q2 cells).
if [[ " $cases " == *" gmg-vs-direct "* ]]; then
  write_case "$work/np1-gmg-vs-direct" direct none 4e5
  mpirun -np 1 "$sealfe" solve "$work/case.prm" > /dev/null
  for n in 2 3; do
    write_case "$work/np$n-gmg-vs-direct" cg-gmg none 4e5
    mpirun -np $n "$sealfe" solve "$work/case.prm" > /dev/null
  done
  methods "$work"/np{1,2,3}-gmg-vs-direct/summary.json direct cg-gmg cg-gmg
  compare "$work/np1-gmg-vs-direct" "$work/np2-gmg-vs-direct" "cg-gmg (2) vs direct (1)" 2
  compare "$work/np1-gmg-vs-direct" "$work/np3-gmg-vs-direct" "cg-gmg (3) vs direct (1)" 3
fi
# `sealfe coefficients` with `auto`: one rank factorises and takes six linearised solves, two and
# three take cg-gmg and the coefficient set's three adjoint solves (one per load, split among the
# ranks). K and D must agree to 1e-9 of each entry's scale max(sqrt|X_ii X_jj|, |X_ij|): each
# entry is a load functional of a linearised pressure, g.A^-1 b, and the adjoint solve's error is
# bounded as for the loads above (1e-12 |z||b|); the operating point's CG error enters b alike.
if [[ " $cases " == *" coefficients "* ]]; then
  for n in 1 2 3; do
    write_case "$work/np$n-coefficients" auto none 4e5
    mpirun -np $n "$sealfe" coefficients "$work/case.prm" > /dev/null
  done
  python3 - "$work"/np{1,2,3}-coefficients/summary.json <<'PY'
import json, math, sys
runs = [json.load(open(f)) for f in sys.argv[1:]]
assert [r["mpi_ranks"] for r in runs] == [1, 2, 3]
methods = [r["linear_solver"]["method"] for r in runs]
solves = [r["coefficient_linear_solver"]["solves"] for r in runs]
print(f"coefficients: linear solver {methods}, coefficient-set solves {solves}")
ok = methods == ["direct", "cg-gmg", "cg-gmg"] and solves == [6, 3, 3]
for r in runs[1:]:
    worst = 0.0
    for m in ("stiffness", "damping"):
        x, y = runs[0][m], r[m]
        for i in range(3):
            for j in range(3):
                scale = max(math.sqrt(abs(x[i][i] * x[j][j])), abs(x[i][j]))
                worst = max(worst, abs(y[i][j] - x[i][j]) / scale)
    print(f"coefficients: max relative difference of K, D, 1 vs {r['mpi_ranks']} ranks = {worst:.2e}")
    ok = ok and worst < 1e-9
sys.exit(0 if ok else 1)
PY
fi
# the dimpled face on the mesh gmsh generates (rank 0 generates and reads it, the ranks get its
# text), with its JFO coarse levels; needs the gmsh program
if command -v gmsh > /dev/null && [[ " $cases " == *" fitted "* ]]; then
  for n in 1 2; do
    sed "s|^set Output directory.*|set Output directory = $work/np$n-fitted|" \
      "$(dirname "$0")/../prm/dimples_fitted.prm" > "$work/fitted.prm"
    mpirun -np $n "$sealfe" solve "$work/fitted.prm" > /dev/null
  done
  compare "$work/np1-fitted" "$work/np2-fitted" "dimples_fitted"
fi
