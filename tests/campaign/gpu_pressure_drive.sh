#!/bin/sh
# inlet_force on the GPU (docs/permeability.md "Pressure-driven runs"): the CI slit, padded with a
# 4 rc reservoir, driven by inlet_force in the reservoir, run once with --backend cpu and once with
# --backend cuda (one rank each, the same scene and seed). Prints, per backend, q, the measured
# dp and G, the total inlet force per area and the momentum balance dp / (F / A); fails when the
# CUDA run's balance is off by more than 3 errors of dp + 0.03, or when the two backends' mean inlet
# force per area (a count of particles in the slab) differ by more than 2% (they sample different
# noise, the same physics). Not a ctest (the ctest machine has no GPU); run on a GPU machine:
# usage: tests/campaign/gpu_pressure_drive.sh BUILD_DIR [STEPS] [WORKDIR]
set -u
B=$1; N=${2:-6000}; W=${3:-/tmp/gpu-pressure-drive}
M=$B/bin/mdpore
mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR="$W/cache"
$M image make slit --width 8 --wall 4 --length 12 --depth 8 -o slit.raw > /dev/null || exit 1
$M image convert slit.raw --pad x=4 -o slitpad.raw > /dev/null || exit 1 # 2 rc on each face
for be in cpu cuda; do
  mkdir -p $be
  cat > $be/scene.yaml <<YAML
name: slit_pressure_$be
box: {lo: [0, 0, 0], hi: [10, 8, 4], periodic: [true, true, true]}
species:
  - {name: liquid, mass: 1.0}
  - {name: quartz, mass: 1.0, frozen: true}
pairs: {default: {A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}
density_kernel: warren
kT: 1.0
effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}, bounce_back: {},
          inlet_force: {liquid: [0.5, 0, 0], along: x, slab: [9, 10], sample: [2, 8]}}
geometry: {image: $W/slitpad.raw, rc_per_voxel: 0.5, flow_axis: x, fluid_density: 6.2,
           species: {fluid: liquid, inorganic: quartz}}
initial: {temperature: 1.0}
run: {dt: 0.01, steps: $N, seed: 5}
output: {flux: {every: 10, file: flux.csv, axis: x}, summary: summary.json, progress: false}
YAML
  (cd $be && $M run --backend $be scene.yaml > run.log 2>&1) || { echo "$be run failed:"; tail -5 $be/run.log; exit 1; }
done
/usr/bin/python3 - <<'PY'
import json, sys
r = {b: json.load(open(f"{b}/summary.json"))["flux"] for b in ("cpu", "cuda")}
bad = 0
for b, f in r.items():
    p = f["pressure_drop"]
    print(f"{b:4s}: q = {f['q']:.5g} +- {f['q_err']:.2g}  dp = {p['dp']:.4g} +- {p['dp_err']:.2g}  "
          f"G = {p['G']:.4g}  F/A = {p['inlet_force_per_area']:.4g}  dp/(F/A) = {p['dp_over_force_per_area']:.3f}")
p = r["cuda"]["pressure_drop"]
if abs(p["dp_over_force_per_area"] - 1) > 3 * p["dp_err"] / p["dp"] + 0.03:
    print("FAIL: CUDA momentum balance"); bad = 1
fa = [r[b]["pressure_drop"]["inlet_force_per_area"] for b in ("cpu", "cuda")]
if abs(fa[1] / fa[0] - 1) > 0.02:
    print("FAIL: inlet force per area differs between the backends"); bad = 1
print("ok" if not bad else "failed")
sys.exit(bad)
PY
