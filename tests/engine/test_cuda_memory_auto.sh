#!/bin/sh
# CUDA memory modes: with --gpu-memory auto the engine keeps the fast mode
# (neighbour lists) when it fits and takes the compact mode (no lists) when it would not. The test
# pretends the device has 1 MB free (MDPORE_CUDA_TEST_FREE_BYTES): the run must say it chose the
# compact mode and why, and finish; the same scene without the pretence runs in the fast mode.
# Both start from the same configuration and compute the same forces, so their step-50 thermo lines
# agree (printed; asserted to 1e-6 in T). A third run has the lists' first allocation fail
# (MDPORE_CUDA_TEST_LIST_FAIL: the switch during a run, after the static tail of the wall particles
# was placed, which the compact mode does not keep): it must say why, finish, and agree too.
# Skipped (exit 77) without a GPU.
# Usage: test_cuda_memory_auto.sh MDPORE SCENE
set -u
M=$1; S=$2
W=cuda_memory_auto_test; rm -rf $W; mkdir -p $W; cd $W || exit 1
if ! $M run --backend cuda --explain $S > /dev/null 2> probe.txt; then
  echo "skipped: no GPU ($(sed 's/.*available: //' probe.txt))"; exit 77
fi
MDPORE_CUDA_TEST_FREE_BYTES=1000000 $M run --backend cuda --steps 50 --output-dir auto $S \
  > auto.out 2> auto.err || { echo "FAIL: the auto run failed"; cat auto.err; exit 1; }
$M run --backend cuda --steps 50 --output-dir fast $S > fast.out 2> fast.err ||
  { echo "FAIL: the fast run failed"; cat fast.err; exit 1; }
grep -q "GPU memory mode compact" auto.out || { echo "FAIL: auto did not choose compact"; cat auto.out; exit 1; }
grep -q "compact memory mode (no neighbour lists): the fast mode would need" auto.err ||
  { echo "FAIL: no reason given for the compact mode"; cat auto.err; exit 1; }
grep -q "GPU memory mode fast" fast.out || { echo "FAIL: the fast run is not in the fast mode"; exit 1; }
grep "compact memory mode" auto.err
MDPORE_CUDA_TEST_LIST_FAIL=1 $M run --backend cuda --steps 50 --output-dir late $S \
  > late.out 2> late.err || { echo "FAIL: the run whose lists did not fit failed"; cat late.err; exit 1; }
grep -q "compact memory mode (no neighbour lists): no room for neighbour lists" late.err ||
  { echo "FAIL: the run whose lists did not fit gave no reason"; cat late.err; exit 1; }
grep "compact memory mode" late.err
f=$(tail -n 1 fast/thermo.csv)
echo "step-50 thermo, fast:    $f"
for run in auto late; do
  a=$(tail -n 1 $run/thermo.csv)
  echo "step-50 thermo, compact ($run): $a"
  awk -F, -v a="$a" -v f="$f" -v r=$run 'BEGIN { split(a, x, ","); split(f, y, ",");
    d = x[3] - y[3]; if (d < 0) d = -d; if (x[1] != y[1] || d > 1e-6) { print "FAIL: T differs (" r ")"; exit 1 } }' || exit 1
done
echo "cuda memory auto: compact when the lists would not fit, same thermo as the fast mode"
