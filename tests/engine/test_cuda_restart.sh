#!/bin/sh
# CUDA path: a checkpoint/restart continues identically on one GPU (the device keeps the
# cell order of the checkpoint: the stable cell sort leaves a sorted set as it is, and the forces of
# the checkpoint are kept). A straight 200-step run and 100 steps + restart + 100 steps write the
# same step-200 dump frame (10 digits) and thermo line. Skipped (exit 77) without a GPU.
# Usage: test_cuda_restart.sh MDPORE SCENE
set -u
M=$1; S=$2
W=cuda_restart_test${MDPORE_GPU_MEMORY:+_$MDPORE_GPU_MEMORY}; rm -rf $W; mkdir -p $W; cd $W || exit 1
if ! $M run --backend cuda --explain $S > /dev/null 2> probe.txt; then
  echo "skipped: no GPU ($(sed 's/.*available: //' probe.txt))"; exit 77
fi
run1() { $M run --backend cuda "$@" > /dev/null || { echo "FAIL: $*"; exit 1; }; }
run1 --output-dir straight $S
run1 --steps 100 --output-dir first $S
run1 --steps 100 --restart first/restart.h5 --output-dir second $S
frame() { awk '/ITEM: TIMESTEP/{getline; s=$1} s==200' "$1"; }
[ -n "$(frame straight/dump.lammpstrj)" ] || { echo "FAIL: no step-200 dump frame"; exit 1; }
[ "$(frame straight/dump.lammpstrj)" = "$(frame second/dump.lammpstrj)" ] ||
  { echo "FAIL: step-200 dump frames differ"; exit 1; }
[ "$(tail -n 1 straight/thermo.csv)" = "$(tail -n 1 second/thermo.csv)" ] || { echo "FAIL: thermo differs"; exit 1; }
[ "$(frame straight/dump.lammpstrj)" != "$(awk '/ITEM: TIMESTEP/{getline; s=$1} s==100' straight/dump.lammpstrj)" ] ||
  { echo "FAIL: the comparison cannot fail (steps 100 and 200 equal)"; exit 1; }
echo "cuda restart: step-200 dump frame and thermo identical"
