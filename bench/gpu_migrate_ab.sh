#!/bin/sh
# One GPU against two, the migration through the host arrays (MDPORE_CUDA_HOST_MIGRATE=1,
# the CPU path's migrate_particles on downloaded fields) against the records path (one download,
# migrate_records, one upload), each with the GPU idle probes (MDPORE_CUDA_IDLE=1: device time of
# the migration, the ghost selection and the step's end, ms per step) and the per-phase host times.
# usage: bench/gpu_migrate_ab.sh BUILD_DIR [OUTDIR] [CASES]   CASES default "bulk 118|porous 72"
#   HM_LIST: the MDPORE_CUDA_HOST_MIGRATE values to run in turn (default "1 0 1 0")
set -u
B=$1; O=${2:-migrate-ab}; mkdir -p "$O"
CASES=${3:-"bulk 118|porous 72"}
export GPU_BENCH_PHASES=1 MDPORE_CUDA_IDLE=1
echo "$CASES" | tr '|' '\n' | while read -r case; do
  "$B/bin/gpu_bench" $case 100 30 cuda < /dev/null
  for hm in ${HM_LIST:-1 0 1 0}; do
    echo "MDPORE_CUDA_HOST_MIGRATE=$hm"
    MDPORE_CUDA_HOST_MIGRATE=$hm mpiexec --allow-run-as-root --oversubscribe --bind-to none -n 2 \
      -x GPU_BENCH_PHASES -x MDPORE_CUDA_IDLE -x MDPORE_CUDA_HOST_MIGRATE \
      "$B/bin/gpu_bench" $case 100 30 cuda < /dev/null
  done
done 2>&1 | grep -v "backend cuda on\|memory mode\|GPU halo staged" | tee "$O/ab.txt"
