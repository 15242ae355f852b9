#!/bin/sh
# Several GPUs of one host, in one call: weak scaling (the box grows with the ranks along
# x) and strong scaling (GPU_BENCH_STRONG=1: the same box) of bulk fluid and the paper's porous
# medium on 1, 2, 4, ... of the visible GPUs (one per rank), with the per-phase host times; then
# the ~240M-particle porous medium across all GPUs (strong). Efficiency = MPS(n) / (n MPS(1)).
# usage: bench/gpu_scaling.sh BUILD_DIR [OUTDIR] [CASES]   CASES default "bulk 118|porous 72"
#   SCALING_BIG=0 skips the 240M run.
set -u
B=$1; O=${2:-gpu-scaling}; mkdir -p "$O"
CASES=${3:-"bulk 118|porous 72"}
G=$(nvidia-smi -L | wc -l)
export GPU_BENCH_PHASES=1
nps=1; n=2
while [ "$n" -le "$G" ]; do nps="$nps $n"; n=$((n * 2)); done
mpi() { # mpi NP STRONG(0|1) ARGS...: gpu_bench on NP ranks
  np=$1; strong=$2; shift 2
  if [ "$np" = 1 ]; then
    GPU_BENCH_STRONG=$strong "$B/bin/gpu_bench" "$@" < /dev/null
  else
    GPU_BENCH_STRONG=$strong mpiexec --allow-run-as-root --oversubscribe --bind-to none -n "$np" \
      -x GPU_BENCH_PHASES -x GPU_BENCH_STRONG "$B/bin/gpu_bench" "$@" < /dev/null # (mpiexec
    # would read the case list from stdin)
  fi
}
echo "$CASES" | tr '|' '\n' | while read -r case; do
  for np in $nps; do mpi "$np" 0 $case 100 30 cuda; done
  for np in $nps; do [ "$np" = 1 ] || mpi "$np" 1 $case 100 30 cuda; done
done 2>&1 | grep -v "backend cuda on\|memory mode\|GPU halo staged" | tee "$O/scaling.txt"
if [ "${SCALING_BIG:-1}" = 1 ]; then
  mpi "$G" 1 porous 354 100 20 cuda 2>&1 | grep -v "backend cuda on\|GPU halo staged" | tee "$O/big.txt"
fi
