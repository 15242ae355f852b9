#!/usr/bin/env bash
# The hard cases on a machine with several GPUs, in one call (docs/stability.md, "On the GPU
# backend"): each rank its own GPU (several ranks sharing one GPU are synchronisation-bound on these
# small systems: 10-25x slower), so
#   1. hard_cases.py --backend cuda --ranks 4 on GPUs 0-3 (when 4 are visible);
#   2. then, concurrently: the long run (long_run.sh, 10^6 steps) on the last GPU, and
#      hard_cases.py --ranks 1,2 on GPUs 0-1;
# results in OUT/hard_r4, OUT/hard_r12 (hard_cases_cuda.{md,json}) and OUT/long_run.txt.
# usage: validation/stability/run_gpu.sh MDPORE OUT [LONG_STEPS (1000000)] [LONG_TIMEOUT_S (380)]
#   HARD4_TIMEOUT_S (160): the limit of step 1 (its log keeps the runs that ended in time)
set -u
M=$(realpath "$1"); O=$2; STEPS=${3:-1000000}; LT=${4:-380}
mkdir -p "$O"
HERE=$(cd "$(dirname "$0")" && pwd)
G=$(nvidia-smi -L | wc -l)
export MDPORE="$M"
if [ "$G" -ge 4 ]; then
  CUDA_VISIBLE_DEVICES=0,1,2,3 timeout "${HARD4_TIMEOUT_S:-160}" python3 "$HERE/hard_cases.py" --backend cuda --ranks 4 \
    --out "$O/hard_r4" > "$O/hard_r4.log" 2>&1
  tail -3 "$O/hard_r4.log"
fi
last=$((G - 1))
CUDA_VISIBLE_DEVICES=$last timeout "$LT" bash "$HERE/long_run.sh" "$M" "$STEPS" cuda /tmp/mdpore-long-run \
  > "$O/long_run.txt" 2>&1 &
lr=$!
CUDA_VISIBLE_DEVICES=0,1 python3 "$HERE/hard_cases.py" --backend cuda --ranks 1,2 --out "$O/hard_r12" \
  > "$O/hard_r12.log" 2>&1
tail -3 "$O/hard_r12.log"
wait $lr
echo "long run exit $?"
cat "$O/long_run.txt"
