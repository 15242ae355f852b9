#!/bin/sh
# What the density cache of static frozen particles saves on the CPU (plan.density_cache,
# meso/backend/cpu/density_pass.c): a wall-heavy image scene, the POREMAPS BCC sphere pack (100^3
# voxels, porosity 0.30) at RC_PER_VOXEL rc per voxel (default 0.25: box 25^3 rc, about half of the
# particles are wall particles), geometry + bounce_back, mDPD water, body force 0.02, run STEPS steps
# (default 300) on NP ranks (default 1) with MDPORE_DENSITY_CACHE=0 (off) and with the cache (on),
# alternating off / on ROUNDS times (default 2) in the same call. Prints each run's particle-steps
# per second (all particles, from the summary) and the loop time.
# usage: bench/cpu_walls.sh BUILD_DIR BCC_RAW [RC_PER_VOXEL] [STEPS] [NP] [ROUNDS] [WORKDIR]
set -u
B=$1; BCC=$2; S=${3:-0.25}; N=${4:-300}; NP=${5:-1}; R=${6:-2}; W=${7:-/tmp/cpu-walls}
M=$B/bin/mdpore
mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR="$W/cache"
$M image convert "$BCC" --dims 100x100x100 --labels pore=0,inorganic=1 -o bcc.h5 > /dev/null || exit 1
L=$(awk "BEGIN { print 100 * $S }")
cat > bcc.yaml <<YAML
name: cpu_walls_bcc
box: {lo: [0, 0, 0], hi: [$L, $L, $L], periodic: true}
species:
  - {name: liquid}
  - {name: wall, frozen: true}
pairs:
  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}
effects:
  mdpd_attraction: {}
  mdpd_repulsion: {}
  dpd_thermostat: {}
  body_force: {liquid: [0.02, 0, 0]}
  bounce_back: {}
geometry:
  image: bcc.h5
  labels: "pore=0,inorganic=1"
  rc_per_voxel: $S
  flow_axis: x
  species: {fluid: liquid, inorganic: wall}
run: {dt: 0.01, steps: $N, seed: 5}
output:
  thermo: {every: 100, file: thermo.csv}
  summary: summary.json
  progress: false
YAML
run() { # $1 = 0 (cache off) or 1 (on), $2 = round
  if [ "$NP" -gt 1 ]; then L1="mpiexec -n $NP --oversubscribe"; else L1=""; fi
  MDPORE_DENSITY_CACHE=$1 $L1 $M run --backend cpu --output-dir out-$1-$2 bcc.yaml > run-$1-$2.log 2>&1 ||
    { tail -5 run-$1-$2.log; return; }
  /usr/bin/python3 - "out-$1-$2/summary.json" "$1" "$2" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["timing"]
print(f"cache {'on ' if sys.argv[2] == '1' else 'off'} round {sys.argv[3]}: particles {t['particles']}, "
      f"{t['particle_steps_per_second'] / 1e6:.3f} M particle-steps/s, loop {t['loop_seconds']:.2f} s")
PY
}
i=1
while [ $i -le "$R" ]; do
  run 0 $i
  run 1 $i
  i=$((i + 1))
done
grep -E "^  (walls|particles):" run-1-1.log
