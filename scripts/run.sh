#!/usr/bin/env bash
# First README command: install what running needs and build the executable alone if needed
# (scripts/setup.sh run), then solve the built-in default seal.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh" run
cd "$here"
exec build/sealfe solve "$@"
