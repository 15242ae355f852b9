#!/bin/sh
# Strict wall penetration (geometry.strict): an 8-voxel slit (0.5 rc voxels) whose fluid is pushed
# into the wall by a body force normal to it, without a boundary effect: the run stops at the first
# thermo sample with a particle inside the solid, naming the particle, its voxel, the step and what
# to try, with a non-zero exit. With bounce_back the same push leaves no particle in the solid and
# the run ends normally.
# Usage: test_guard_penetration.sh MDPORE
set -u
M=$1
W=guard_penetration_test; rm -rf $W; mkdir -p $W; cd $W || exit 1
fail() { echo "FAIL: $*"; exit 1; }
$M image make slit --width 8 --wall 4 --length 8 --depth 8 -o slit.h5 > /dev/null || fail "image"
cat > strict.yaml <<'YAML'
name: guard_penetration
box: {lo: [0, 0, 0], hi: [4, 8, 4]}
species:
  - {name: liquid}
  - {name: quartz, frozen: true}
pairs:
  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}
effects:
  mdpd_attraction: {}
  mdpd_repulsion: {}
  dpd_thermostat: {}
  body_force: {liquid: [0, 3.0, 0]}
geometry:
  image: slit.h5
  rc_per_voxel: 0.5
  flow_axis: x
  species: {fluid: liquid, inorganic: quartz}
  strict: true
run: {dt: 0.005, steps: 400, seed: 7}
output:
  thermo: {every: 10, file: thermo.csv}
  progress: false
YAML
sed 's/  dpd_thermostat: {}/  dpd_thermostat: {}\n  bounce_back: {}/' strict.yaml > bounce.yaml
if $M run --output-dir strict strict.yaml > strict.out 2> strict.err; then
  fail "strict: a particle in the wall did not stop the run"
fi
for part in "inside solid voxels of slit.h5" "deepest: particle " "voxel (" "step " \
            "Stopping (geometry.strict)" "Try a boundary effect (bounce_back)"; do
  grep -qF "$part" strict.err || { cat strict.err; fail "strict: stderr lacks '$part'"; }
done
grep "Stopping" strict.err
$M run --output-dir bounce bounce.yaml > bounce.out 2> bounce.err || { cat bounce.err; fail "bounce_back run stopped"; }
grep -q "penetrations: 0 of" bounce.out || { cat bounce.out; fail "bounce_back: penetrations not 0"; }
grep "penetrations:" bounce.out
echo "strict penetration stops with particle, voxel, step and advice; bounce_back keeps it at 0"
