#!/bin/sh
# The kernels of a few steps on one GPU and on rank 0 of two (ncu, durations only; the
# other rank runs unprofiled), to see what the several-rank step adds to the GPU's work.
# usage: bench/gpu_step_kernels.sh BUILD_DIR [OUTDIR] [CASE]   CASE default "porous 72"
set -u
B=$1; O=${2:-step-kernels}; mkdir -p "$O"; CASE=${3:-"porous 72"}
M="--clock-control none --metrics gpu__time_duration.sum --csv"
timeout 300 ncu $M --launch-skip 1200 --launch-count 80 "$B/bin/gpu_bench" $CASE 40 30 cuda \
  > "$O/one.csv" 2> "$O/one.err" < /dev/null
echo "one GPU: $(wc -l < "$O/one.csv") lines"
timeout 300 mpiexec --allow-run-as-root --oversubscribe --bind-to none -n 2 sh -c \
  "if [ \"\$OMPI_COMM_WORLD_RANK\" = 0 ]; then exec ncu $M --launch-skip 1600 --launch-count 120 \
   $B/bin/gpu_bench $CASE 40 30 cuda > $O/two.csv 2> $O/two.err; \
   else exec $B/bin/gpu_bench $CASE 40 30 cuda > /dev/null; fi" < /dev/null
echo "two GPUs, rank 0: $(wc -l < "$O/two.csv") lines"
