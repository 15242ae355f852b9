#!/bin/sh
# The rock campaigns on a GPU machine (the device tool): build mdpore with CUDA (bench/device_build.sh,
# only the binaries the runs need), run every scene of WORK/runs.txt JOBS at once, starting none after
# TIME_BOX seconds, and pack the run folders' results into $OUT/rockruns.tgz for `rocks.py report` here.
# usage: sh validation/rocks/run_gpu.sh WORK [JOBS] [TIME_BOX]
set -u
W=$1; JOBS=${2:-4}; BOX=${3:-400}
t0=$(date +%s)
set -- "$PWD/build-dev"  # device_build.sh reads its folder from $1
DEVICE_TARGETS="mdpore gpu_bench" . bench/device_build.sh
[ "$DEVICE_BUILD_OK" = 1 ] || exit 1
echo "build: $(( $(date +%s) - t0 )) s"
nvidia-smi --query-gpu=name,memory.total,clocks.sm,clocks.max.sm --format=csv,noheader
export MDPORE="$PWD/build-dev/bin/mdpore" MDPORE_CACHE_DIR="${MDPORE_CACHE_DIR:-$PWD/build-dev/cache}"
git rev-parse --short HEAD 2>/dev/null
python3 validation/rocks/rocks.py device "$W" --jobs "$JOBS" --time-box "$BOX"
(cd "$W" && find . \( -name summary.json -o -name run.log -o -name flux.csv \) -print | tar czf "${OUT:-/tmp}/rockruns.tgz" -T -)
echo "packed $(tar tzf "${OUT:-/tmp}/rockruns.tgz" | wc -l) files; total $(( $(date +%s) - t0 )) s"
