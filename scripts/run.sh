#!/usr/bin/env bash
# First README command: set up if needed, then solve the built-in default seal.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh"
cd "$here"
exec build/sealfe solve "$@"
