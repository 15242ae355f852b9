#!/usr/bin/env bash
# Long libFuzzer runs of one input reader (docs/fuzzing.md):
#   scripts/fuzz.sh TARGET [SECONDS]     TARGET: one of $targets below (default 300 s)
# Builds the clang ASan+UBSan+libFuzzer tree in $MDPORE_FUZZ_BUILD (default build-fuzz/) when
# needed, then fuzzes from the seed corpus tests/fuzz/corpus/TARGET. New inputs are kept in the build
# folder (BUILD/tests/fuzz/work/TARGET/corpus), never in the repository; a crash, hang or sanitizer
# report stops the run, leaves the input as BUILD/tests/fuzz/work/TARGET/crash-* (or timeout-*,
# oom-*, leak-*) and exits non-zero. Extra libFuzzer flags: MDPORE_FUZZ_FLAGS="-jobs=2".
# MDPORE_FUZZ_NO_BUILD=1 runs the executable as built (no cmake step: runs one after another while
# the tree is being built for other targets).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
targets="scene image_raw image_hdf5 image_tiff flow_table lammps_data darcy_config couple_config kr_table pc_curve relperm_manifest campaign_args campaign_folder image_ops geometry"
target=${1:-}
seconds=${2:-300}
if [ -z "$target" ] || ! echo " $targets " | grep -q " $target "; then
  echo "usage: $0 TARGET [SECONDS]   (TARGET: ${targets// /, })" >&2
  exit 2
fi
command -v clang >/dev/null || { echo "$0: clang not found (Debian: apt-get install clang)" >&2; exit 2; }
build=${MDPORE_FUZZ_BUILD:-$root/build-fuzz}
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMDPORE_FUZZ=ON >/dev/null
fi
if [ -z "${MDPORE_FUZZ_NO_BUILD:-}" ]; then
  cmake --build "$build" -j "${MDPORE_BUILD_JOBS:-2}" --target "fuzz_$target" >/dev/null
fi
work=$build/tests/fuzz/work/$target
mkdir -p "$work/corpus"
exe=$build/bin/fuzz_$target
[ -x "$exe" ] || { echo "$0: $exe was not built (is its module enabled: TIFF, PETSc?)" >&2; exit 2; }
echo "fuzzing $target for $seconds s (corpus $work/corpus, seeds tests/fuzz/corpus/$target)"
set +e
# shellcheck disable=SC2086
"$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -close_fd_mask=3 \
  -print_final_stats=1 -artifact_prefix="$work/" ${MDPORE_FUZZ_FLAGS:-} \
  "$work/corpus" "$root/tests/fuzz/corpus/$target"
rc=$?
set -e
if [ $rc -ne 0 ]; then
  echo "$0: $target: a finding (exit $rc); its input: $(ls -t "$work"/crash-* "$work"/timeout-* "$work"/oom-* "$work"/leak-* 2>/dev/null | head -1)"
  echo "replay it: $build/bin/fuzz_${target}_replay FILE (or $exe FILE); once fixed, copy it to tests/fuzz/corpus/$target/crash_NAME"
fi
exit $rc
