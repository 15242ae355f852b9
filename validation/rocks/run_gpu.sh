#!/bin/sh
# The rock campaigns on a GPU machine (the device tool): build mdpore with CUDA (bench/device_build.sh,
# only the binaries the runs need) unless PREBUILT names a binary built so before (with its
# .carry/debs), run every scene of WORK/runs.txt that has no result yet, JOBS at once, starting none
# after TIME_BOX seconds and stopping the runs still going at DEADLINE seconds (a stopped run leaves
# no summary and is run again by the next call), then pack the run folders' results, the wall-patch
# databases made here and the binary into $OUT for `rocks.py report` here.
# usage: sh validation/rocks/run_gpu.sh WORK [JOBS] [TIME_BOX] [DEADLINE]
set -u
W=$1; JOBS=${2:-4}; BOX=${3:-400}; DEADLINE=${4:-560}
t0=$(date +%s)
if [ -n "${PREBUILT:-}" ] && [ -x "$PREBUILT" ]; then
  mkdir -p /opt/deps
  for f in .carry/debs/*.deb; do dpkg -x "$f" /opt/deps; done
  export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  export MDPORE="$PWD/$PREBUILT"
else
  set -- "$PWD/build-dev"  # device_build.sh reads its folder from $1
  DEVICE_TARGETS="mdpore gpu_bench" . bench/device_build.sh
  [ "$DEVICE_BUILD_OK" = 1 ] || exit 1
  export MDPORE="$PWD/build-dev/bin/mdpore"
  cp "$MDPORE" "${OUT:-/tmp}/mdpore"
fi
echo "build: $(( $(date +%s) - t0 )) s"
nvidia-smi --query-gpu=name,memory.total,clocks.sm,clocks.max.sm --format=csv,noheader
export MDPORE_CACHE_DIR="${MDPORE_CACHE_DIR:-$PWD/build-dev/cache}"
mkdir -p "$MDPORE_CACHE_DIR"
git rev-parse --short HEAD 2>/dev/null
left=$(( DEADLINE - ($(date +%s) - t0) ))
timeout -s INT "$left" python3 validation/rocks/rocks.py device "$W" --jobs "$JOBS" --time-box "$BOX"
pkill -INT -f "mdpore run" 2>/dev/null; sleep 1
(cd "$W" && find . \( -name summary.json -o -name run.log -o -name flux.csv \) -print | tar czf "${OUT:-/tmp}/rockruns.tgz" -T -)
(cd "$MDPORE_CACHE_DIR" && tar czf "${OUT:-/tmp}/cache.tgz" .)
echo "packed $(tar tzf "${OUT:-/tmp}/rockruns.tgz" | wc -l) files; total $(( $(date +%s) - t0 )) s"
