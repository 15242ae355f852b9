#!/bin/sh
# Image-based porous benchmark, one GPU, in one call: the POREMAPS BCC sphere pack
# (../shared/data/external/poremaps_benchmarks, 100^3 voxels, porosity 0.30) and a random-sphere
# image (100^3, radius 8 voxels, porosity 0.35), each built by the scene path a user takes
# (`geometry:` + bounce_back, walls from the patch database), at RC_PER_VOXEL rc per voxel, run for
# STEPS steps on the GPU; then the paper's ring medium (gpu_bench porous 72) in the same call.
# Prints the builder's report, the summary's particle-steps per second (all particles) and the wall
# time; fluid-only throughput = MPS x fluid / particles.
# With CACHE_AB=1 each image runs twice, the density cache of the static walls off then on
# (MDPORE_DENSITY_CACHE=0 / =1; on the GPU the cache is opt-in; docs/walls.md section 15).
# THERMO_EVERY (default 100): thermo rows, each with the geometry's census (penetrations, pore-core
# density: on the GPU a copy of the particles to the host); with 1000 and STEPS 1000 only the census
# every 500 steps remains, so two runs give the census's cost (bench/RESULTS.md, 2026-11-26
# dbc70cb).
# usage: [BOUNDARY=...] [CACHE_AB=1] [THERMO_EVERY=N] bench/gpu_walls.sh BUILD_DIR BCC_RAW [RC_PER_VOXEL] [STEPS] [WORKDIR]
set -u
B=$1; BCC=$2; S=${3:-1.5}; N=${4:-400}; W=${5:-/tmp/gpu-walls}
# BOUNDARY: bounce_back (default), wall_boundary, or wall_boundary+bounce_back
EFFECTS=$(echo "${BOUNDARY:-bounce_back}" | tr '+' '\n' | sed 's/^/  /; s/$/: {}/')
M=$B/bin/mdpore
mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR="$W/cache"
$M image convert "$BCC" --dims 100x100x100 --labels pore=0,inorganic=1 -o bcc.h5 > /dev/null || exit 1
$M image make random-spheres --size 100 --radius 8 --porosity 0.35 --seed 3 -o rs.h5 > /dev/null || exit 1
L=$(awk "BEGIN { print 100 * $S }")
for img in bcc rs; do
  cat > $img.yaml <<YAML
name: wallbench_$img
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
$EFFECTS
geometry:
  image: $img.h5
  labels: "pore=0,inorganic=1"
  rc_per_voxel: $S
  flow_axis: x
  species: {fluid: liquid, inorganic: wall}
run: {dt: 0.01, steps: $N, seed: 5}
output:
  thermo: {every: ${THERMO_EVERY:-100}, file: thermo.csv}
  summary: summary.json
  progress: false
YAML
  # CACHE_AB=1: each image with the density cache of the static walls off (MDPORE_DENSITY_CACHE=0),
  # then on, in the same call (docs/walls.md, "Wall densities computed once")
  modes=default
  [ -n "${CACHE_AB:-}" ] && modes="0 1"
  for cache in $modes; do
    log=$img.log
    [ -n "${CACHE_AB:-}" ] && log=$img-cache$cache.log && echo "$img, density cache $cache:"
    [ "$cache" = default ] && unset MDPORE_DENSITY_CACHE || export MDPORE_DENSITY_CACHE=$cache
    /usr/bin/time -f "$img: wall time %e s, max RSS %M kB" $M run --backend cuda \
      --output-dir out-$img-$cache $img.yaml > $log 2>&1 || tail -5 $log
    grep -E "^  (walls|wall particles|fluid|particles):|performance|penetrations|T = |wall time" $log
  done
done
$B/bin/gpu_bench porous 72 100 50 cuda 2>&1 | tail -1
