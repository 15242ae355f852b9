#!/usr/bin/env bash
# Configures and builds mdpore into build/ (or $MDPORE_BUILD_DIR). Extra arguments go to cmake.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bdir=${MDPORE_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$bdir" -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE:-Release} "$@" >/dev/null
cmake --build "$bdir" -j "$(nproc)"
