#!/bin/sh
# The paper's porous-medium case generator (cases/make_porous_medium.py) makes a scene that mdpore runs:
# 2 x 2 cells (7676 particles: 4 rings of frozen wall particles + fluid), 100 steps with g_z = 0.02 on
# the fluid. Asserts: the particle count in thermo.csv equals the generated one, and the fluid picked up
# z momentum in the direction of the body force (at least a quarter of the free impulse N_fluid g t;
# the walls' drag takes the rest).
# Usage: test_case_porous_medium.sh MDPORE PYTHON GENERATOR
set -u
M=$1; PY=$2; GEN=$3
W=porous_case_test; rm -rf $W; mkdir -p $W; cd $W || exit 1
$PY $GEN 2 . --steps 100 || { echo "FAIL: generator"; exit 1; }
$M run porous_medium_2.yaml > run.log 2>&1 || { echo "FAIL: mdpore run"; cat run.log; exit 1; }
$PY - <<'PYEOF' || exit 1
import csv, math
rows = [r for r in csv.DictReader(l for l in open("thermo.csv") if not l.startswith("#"))]
last = rows[-1]
n_gen = int(open("porous_medium_2.data").read().split(" atoms")[0].split()[-1])
n_fluid = 4 * round(6.2 * (256 - math.pi * 49) * 2)
free = n_fluid * 0.02 * float(last["time"])
print(f"N = {last['N']} (generated {n_gen}); pz = {float(last['pz']):.2f} (free impulse {free:.2f})")
assert int(last["N"]) == n_gen, "particle count differs from the data file"
assert free > 0 and float(last["pz"]) > 0.25 * free, "the fluid did not accelerate along +z"
PYEOF
echo "porous-medium case: generated, run, driven along +z"
