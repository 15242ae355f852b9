#!/bin/bash
# A long run on a porous image (docs/stability.md): a simple-cubic sphere array
# (c = 0.125, 4^3 cells of 6.4 rc at 0.4 rc per voxel, 107,741 particles), bounce_back walls,
# g = 0.02, dt 0.01, STEPS steps (default 10^6 = 10^4 tau) on BACKEND (default cuda), then the drift
# of T, pressure and particle count between the first and the last 10% of the thermo rows, the
# summary's penetrations and flux, and the density drift (long_run_density.py: the mean local mDPD
# density and the fluid's number-density profiles, from a dump every STEPS/50 steps).
# usage: validation/stability/long_run.sh MDPORE_BINARY [STEPS] [BACKEND] [WORKDIR]
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
M=$1; STEPS=${2:-1000000}; BACKEND=${3:-cuda}; W=${4:-/tmp/mdpore-long-run}
mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR=${MDPORE_CACHE_DIR:-$W/cache}
"$M" image make spheres --cell 16 --c 0.125 --cells 4 -o spheres.h5 > /dev/null || exit 1
cat > scene.yaml <<YAML
name: long_run
box: {lo: [0, 0, 0], hi: [25.6, 25.6, 25.6], periodic: [true, true, true]}
species:
- {name: liquid, mass: 1.0}
- {name: wall, mass: 1.0, frozen: true}
pairs: {default: {A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}
density_kernel: warren
kT: 1.0
effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}, body_force: {liquid: [0.02, 0, 0]}, bounce_back: {}}
geometry: {image: spheres.h5, rc_per_voxel: 0.4, flow_axis: x, fluid_density: 6.2, species: {fluid: liquid, inorganic: wall}}
initial: {temperature: 1.0}
run: {dt: 0.01, steps: $STEPS, seed: 3}
output: {thermo: {every: $(( STEPS / 100 > 0 ? STEPS / 100 : 1 )), file: thermo.csv}, flux: {every: $(( STEPS / 1000 > 0 ? STEPS / 1000 : 1 )), file: flux.csv, axis: x}, dump: {every: $(( STEPS / 50 > 0 ? STEPS / 50 : 1 )), file: dump.lammpstrj}, summary: summary.json, progress: false}
YAML
"$M" run --backend "$BACKEND" scene.yaml > run.log 2>&1
rc=$?
grep -E "performance|penetrations:|flux along|steady|NOT|stopped" run.log
awk -F, '!/^#/ && $1 != "step" && $1 != "" {n++; t[n]=$3; p[n]=$11; N[n]=$12}
  END {m=int(n/10); if (m < 1) m = 1; a=0; b=0; pa=0; pb=0
       for (i=2; i<=m+1; i++) {a+=t[i]; pa+=p[i]}; for (i=n-m+1; i<=n; i++) {b+=t[i]; pb+=p[i]}
       printf "drift (first vs last 10%% of %d rows): T %.5f -> %.5f (%+.3g%%), p %.4f -> %.4f (%+.3g%%), N %s -> %s\n",
              n, a/m, b/m, 100*(b-a)/a, pa/m, pb/m, 100*(pb-pa)/pa, N[1], N[n]}' thermo.csv
"${PYTHON:-python3}" "$HERE/long_run_density.py" dump.lammpstrj "$STEPS" || rc=1
exit $rc
