#!/usr/bin/env bash
# Installs what is missing (Debian packages) and builds sealfe (Release) in build/.
# Idempotent and quiet when nothing is missing.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"

packages=(cmake g++ make libdeal.ii-dev libboost-dev libgtest-dev gmsh libvtk9-dev nlohmann-json3-dev
          libbenchmark-dev mpi-default-bin mpi-default-dev python3-numpy python3-matplotlib)
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
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j "$jobs" -- --no-print-directory 2>&1 | grep -Ev "^\[|^Consolidate|^Scanning|^Built target|^make" || true
test -x build/sealfe || { echo "sealfe setup: build failed" >&2; exit 1; }
