#!/bin/sh
# The CUDA path's memory plan: with the device memory counted on capped at 100 kB
# (MDPORE_GPU_MEMORY_LIMIT; the scene's ~1400 slots need ~0.24 MB in the compact mode), the run
# must stop with exit 1 before its device arrays are made, with a message naming the particles,
# the bytes, the memory free and what to try; with --gpu-memory auto it first takes the compact
# mode (the fast one does not fit either). Skipped (exit 77) without a GPU.
# Usage: test_cuda_memory_plan.sh MDPORE SCENE
set -u
M=$1; S=$2
W=cuda_memory_plan_test; rm -rf $W; mkdir -p $W; cd $W || exit 1
if ! $M run --backend cuda --explain $S > explain.txt 2> probe.txt; then
  echo "skipped: no GPU ($(sed 's/.*available: //' probe.txt))"; exit 77
fi
grep -q "GPU (CUDA path, one per rank)" explain.txt || { echo "FAIL: --explain has no device plan"; cat explain.txt; exit 1; }
MDPORE_CUDA_TEST_FREE_BYTES=100000 MDPORE_GPU_MEMORY_LIMIT=100K $M run --backend cuda --steps 2 $S \
  > out.txt 2> err.txt
rc=$?
[ $rc -eq 1 ] || { echo "FAIL: exit $rc (expected 1: refused)"; cat err.txt; exit 1; }
for text in "not enough GPU memory" "compact mode" "MDPORE_GPU_MEMORY_LIMIT" "fewer particles"; do
  grep -q "$text" err.txt || { echo "FAIL: no '$text' in the message"; cat err.txt; exit 1; }
done
grep "not enough GPU memory" err.txt
echo "cuda memory plan: refused before the device arrays, with the sizes and what to try"
