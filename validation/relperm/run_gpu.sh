#!/bin/sh
# The runs of emitted `mdpore relperm` campaigns on a GPU machine (the device tool): build mdpore with
# CUDA (bench/device_build.sh: .carry/debs as it says) unless PREBUILT names a binary built so before,
# run every line of each DIR/commands.txt whose run has no summary yet, JOBS at once over all DIRs,
# starting none after TIME_BOX seconds, then pack the run folders' results into $OUT/relperm_runs.tgz
# (unpack in the repository root here, then `mdpore relperm --collect DIR`).
# usage: sh validation/relperm/run_gpu.sh JOBS TIME_BOX DIR...   (DIR relative to the repository root)
set -u
JOBS=$1; BOX=$2; shift 2
t0=$(date +%s)
if [ -n "${PREBUILT:-}" ] && [ -x "$PREBUILT" ]; then
  mkdir -p /opt/deps
  for f in .carry/debs/*.deb; do dpkg -x "$f" /opt/deps; done
  export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  MDPORE="$PWD/$PREBUILT"
else
  set -- "$PWD/build-dev" "$@"
  DEVICE_TARGETS="mdpore gpu_bench" . bench/device_build.sh
  shift
  [ "$DEVICE_BUILD_OK" = 1 ] || exit 1
  MDPORE="$PWD/build-dev/bin/mdpore"
  cp "$MDPORE" "${OUT:-/tmp}/mdpore"
fi
export MDPORE MDPORE_CACHE_DIR="${MDPORE_CACHE_DIR:-$PWD/build-dev/cache}"
mkdir -p "$MDPORE_CACHE_DIR"
echo "build: $(( $(date +%s) - t0 )) s"
root=$PWD
todo=$(mktemp)
for d in "$@"; do
  while IFS= read -r line; do
    run=$(echo "$line" | sed -n 's/^cd \(runs\/[^ ]*\) .*/\1/p')
    [ -f "$d/$run/summary.json" ] || echo "$d|$line" >> "$todo"
  done < "$d/commands.txt"
done
echo "$(wc -l < "$todo") runs to do, $JOBS at once"
n=0
while IFS='|' read -r d line; do
  if [ $(( $(date +%s) - t0 )) -gt "$BOX" ]; then echo "time box: not started: $d $line"; continue; fi
  (cd "$root/$d" && t=$(date +%s) && sh -c "$line"; echo "$d ${line%% &&*}: exit $?, $(( $(date +%s) - t )) s") &
  n=$((n + 1))
  if [ $((n % JOBS)) -eq 0 ]; then wait; fi
done < "$todo"
wait
(cd "$root" && for d in "$@"; do find "$d/runs" \( -name summary.json -o -name run.log -o -name flux.csv \); done | tar czf "${OUT:-/tmp}/relperm_runs.tgz" -T -)
echo "packed $(tar tzf "${OUT:-/tmp}/relperm_runs.tgz" | wc -l) files; total $(( $(date +%s) - t0 )) s"
