#!/usr/bin/env bash
# One command on a fresh machine: installs what is needed, builds everything, runs the default scene
# (a small mDPD liquid slab) and prints its density and surface tension.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
. "$root/scripts/mpi-env.sh"
mkdir -p "$root/out/default"
cd "$root/out/default"
"$root/build/bin/mdpore" run "$root/cases/default_slab.yaml" "$@"
