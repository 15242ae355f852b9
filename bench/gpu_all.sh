#!/bin/sh
# Everything the GPU path is checked and measured with, in one call (the device machines are lent by
# the half hour): CUDA tests, the two ceilings, the throughput table with its skin sweep, an ncu
# profile of one step. usage: bench/gpu_all.sh BUILD_DIR [OUTDIR]   (logs in OUTDIR, default ./gpu-out)
#   GPU_ALL_PARTS="tests ceilings sweep big ncu multi" picks parts (default: all of them).
set -u
B=$1; O=${2:-gpu-out}; mkdir -p "$O"
parts=${GPU_ALL_PARTS:-"tests ceilings sweep big ncu multi"}
has() { case " $parts " in *" $1 "*) return 0 ;; esac; return 1; }
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv | tee "$O/gpu.txt"
if has tests; then
  (cd "$B" && ctest -L cuda --output-on-failure --timeout 300) > "$O/tests.log" 2>&1
  grep -E "tests passed|Failed|FAIL|skin|setup:|after|cuda restart|T cpu|agree" "$O/tests.log" | head -40
fi
has ceilings && "$B/bin/gpu_ceilings" | tee "$O/ceilings.txt"
if has sweep; then
  # Time and <T>, <p> against the Verlet skin (0 = lists rebuilt every step), ~2.1M particles.
  "$B/bin/gpu_bench" porous 33 200 50 cuda 0,0.1,0.2,0.3,0.4,0.5 | tee "$O/sweep.txt"
  "$B/bin/gpu_bench" bulk 70 200 50 cuda 0,0.2,0.3,0.4 | tee -a "$O/sweep.txt"
fi
if has big; then
  "$B/bin/gpu_bench" porous 72 100 50 cuda 0,-1 | tee "$O/big.txt"
  "$B/bin/gpu_bench" bulk 118 100 50 cuda 0,-1 | tee -a "$O/big.txt"
fi
if has ncu && command -v ncu > /dev/null; then
  # One step after the warm-up: the kernels of a list build and of a step that reuses the lists.
  ncu --clock-control none --launch-skip 400 --launch-count 40 \
      --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,sm__throughput.avg.pct_of_peak_sustained_elapsed,gpu__compute_memory_throughput.avg.pct_of_peak_sustained_elapsed,l1tex__throughput.avg.pct_of_peak_sustained_active,lts__throughput.avg.pct_of_peak_sustained_elapsed,sm__inst_executed_pipe_fma.avg.pct_of_peak_sustained_active,sm__inst_executed_pipe_alu.avg.pct_of_peak_sustained_active,sm__pipe_fma_cycles_active.avg.pct_of_peak_sustained_active,sm__sass_thread_inst_executed_op_ffma_pred_on.sum,sm__sass_thread_inst_executed_op_fadd_pred_on.sum,sm__sass_thread_inst_executed_op_fmul_pred_on.sum,sm__warps_active.avg.pct_of_peak_sustained_active,smsp__thread_inst_executed_per_inst_executed.ratio \
      --csv "$B/bin/gpu_bench" porous 33 30 20 cuda -1 > "$O/ncu.csv" 2> "$O/ncu.err"
  echo "ncu: $(wc -l < "$O/ncu.csv") lines in $O/ncu.csv"
  # NCU_FAST=1: the same step with the fast pair generator (dpd_thermostat rng: fast)
  if [ "${NCU_FAST:-0}" = 1 ]; then
    MDPORE_BENCH_RNG=fast ncu --clock-control none --launch-skip 400 --launch-count 40 \
      --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,sm__throughput.avg.pct_of_peak_sustained_elapsed,sm__inst_executed_pipe_alu.avg.pct_of_peak_sustained_active,sm__pipe_fma_cycles_active.avg.pct_of_peak_sustained_active,smsp__thread_inst_executed_per_inst_executed.ratio \
      --csv "$B/bin/gpu_bench" porous 33 30 20 cuda -1 > "$O/ncu_fast.csv" 2> "$O/ncu_fast.err"
    echo "ncu (rng fast): $(wc -l < "$O/ncu_fast.csv") lines"
  fi
fi
if has slab; then
  # The CI slab (tests/engine/scenes/ci_slab.yaml) on 1 GPU and on every GPU (auto backend).
  G=$(nvidia-smi -L | wc -l)
  for np in 1 $G; do
    mpiexec --allow-run-as-root --oversubscribe -n $np "$B/bin/mdpore" run --output-dir "$O/slab$np" \
      "$(dirname "$0")/../tests/engine/scenes/ci_slab.yaml" 2>&1 | grep -v "^step" | tail -6
  done | tee "$O/slab.txt"
fi
if has multi; then
  # Weak scaling on every visible GPU (one per rank) with and without the overlap of interior passes
  # and host exchanges; the one-GPU figures of the same sizes in the same run.
  G=$(nvidia-smi -L | wc -l)
  MPIRUN="mpiexec --allow-run-as-root --oversubscribe --bind-to none -n $G"
  for c in "porous 72 50 20" "bulk 70 100 20"; do
    "$B/bin/gpu_bench" $c cuda
    $MPIRUN "$B/bin/gpu_bench" $c cuda
    MDPORE_CUDA_OVERLAP=0 $MPIRUN -x MDPORE_CUDA_OVERLAP "$B/bin/gpu_bench" $c cuda
  done 2>&1 | grep -v "backend cuda on" | tee "$O/multi.txt"
fi
