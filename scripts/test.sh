#!/usr/bin/env bash
# One command on a fresh machine: installs what is needed, builds everything and runs the whole ctest suite.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
. "$root/scripts/mpi-env.sh"
cd "$root/build"
ctest --output-on-failure -j "${MDPORE_TEST_JOBS:-2}" "$@"
