#!/usr/bin/env bash
# Second README command: install and build everything the tests need if needed
# (scripts/setup.sh test), then run the default test suite (ctest).
# Long studies carry the ctest label "long" and are not run here.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh" test
cd "$here/build"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec ctest --output-on-failure -LE long -j "$(nproc 2>/dev/null || echo 2)" "$@"
