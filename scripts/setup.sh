#!/usr/bin/env bash
# Installs what is missing (Debian packages) and builds sealfe (Release) in build/.
# Idempotent and quiet when nothing is missing.
#
# usage: setup.sh [run|test]
#   run   what running needs only: the compiler, deal.II, nlohmann-json, MPI and matplotlib for
#         the plots; builds the `sealfe` target alone (scripts/run.sh)
#   test  (default) also GoogleTest, VTK (tests read the VTU output), google-benchmark and gmsh;
#         builds every target, tests included (scripts/test.sh, CI)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"

mode=${1:-test}
case "$mode" in
  run | test) ;;
  *) echo "usage: scripts/setup.sh [run|test]" >&2; exit 2 ;;
esac

# liblz4-dev: the VTU writer compresses with LZ4 (VTK's vtkLZ4DataCompressor).
# libmumps-dev: the sparse direct solver calls MUMPS directly (deal.II's Trilinos and PETSc
# bring it too).
# libopenblas0-pthread: an optimised BLAS behind the reference one Debian links by default (the
# MUMPS factorisations of big cavitation systems run their dense fronts in it: 13.4 -> 9.4 s at
# 1e6 unknowns, doc/performance.md "Direct solver"), multithreaded: sealfe gives it the rank's
# threads (numerics::use_blas_threads; doc/performance.md, Session 37). The alternatives system
# prefers it to a single-threaded libopenblas0-serial installed beside it.
packages=(cmake g++ make libdeal.ii-dev libboost-dev nlohmann-json3-dev mpi-default-bin
          mpi-default-dev python3-numpy python3-matplotlib libopenblas0-pthread liblz4-dev
          libmumps-dev)
if [ "$mode" = test ]; then
  packages+=(libgtest-dev gmsh libvtk9-dev libbenchmark-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "sealfe setup: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
quiet() { grep -Ev "^\[|^Consolidate|^Scanning|^Built target|^make" || true; }
if [ "$mode" = run ]; then
  # A build directory made by the test mode keeps its tests; only the executable is built.
  if [ ! -f build/CMakeCache.txt ]; then
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSEALFE_BUILD_TESTS=OFF >/dev/null
  fi
  cmake --build build -j "$jobs" --target sealfe -- --no-print-directory 2>&1 | quiet
else
  # A build directory made by the run mode is switched to build the tests.
  if [ ! -f build/CMakeCache.txt ] || grep -q "^SEALFE_BUILD_TESTS:BOOL=OFF" build/CMakeCache.txt; then
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSEALFE_BUILD_TESTS=ON >/dev/null
  fi
  cmake --build build -j "$jobs" -- --no-print-directory 2>&1 | quiet
fi
test -x build/sealfe || { echo "sealfe setup: build failed" >&2; exit 1; }
