#!/usr/bin/env bash
# The main job, one command on a fresh machine: installs what is needed, builds everything, then runs
# a small permeability campaign (docs/permeability.md) on an image mdpore makes itself: a simple-cubic
# array of spheres at solid fraction 0.125 (12^3 voxels of 0.5 rc: one 6 rc cell), flow along x.
# It prints k from the mDPD runs (rc^2, m^2, nD; superficial-velocity convention) with its error,
# OpenFOAM's k on the SAME voxels (`mdpore foam`, when OpenFOAM is installed) and Zick & Homsy's
# value for the smooth spheres. Then the same on a 16^3 crop of a real rock (a Berea sandstone
# micro-CT image, cases/rock), and the end-to-end coupled demo (mdpore couple, below).
# Extra arguments go to `mdpore permeability` (e.g. --np 4). Output in out/main/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
. "$root/scripts/mpi-env.sh"
m="$root/build/bin/mdpore"
out="$root/out/main"
mkdir -p "$out"
cd "$out"
# 1. A permeability campaign on one image
"$m" image make spheres --cell 12 --c 0.125 --cells 1 -o spheres_c0.125.h5 > image.json
np=$(( $(nproc) >= 2 ? 2 : 1 ))
set +e
"$m" permeability spheres_c0.125.h5 --axis x --np "$np" --workdir campaign "$@"
camp_rc=$?
set -e
# exit 3: the runs define no Darcy range (the report above says why); anything else is a failure
[ "$camp_rc" -eq 0 ] || [ "$camp_rc" -eq 3 ] || { echo "mdpore permeability failed (exit $camp_rc)"; exit 1; }
# foam on the voxel mesh and with each voxel cut in 2^3 cells: the 2.3 rc gaps are 4-5 voxels wide,
# where the voxel mesh alone reads several % high; the continuum k of these voxels is extrapolated
# from the two (foam_continuum in validation/permeability/sphere_array.py; docs/permeability.md, 7b)
foam=""
if "$m" foam spheres_c0.125.h5 --axis x > foam.json 2> foam.log &&
   "$m" foam spheres_c0.125.h5 --axis x --refine 2 > foam_r2.json 2>> foam.log; then
  foam=foam.json
else
  echo "mdpore foam: not run ($(tail -1 foam.log)); the OpenFOAM comparison is skipped"
fi
python3 - "$foam" "$root" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2] + "/validation/permeability")
from sphere_array import foam_k_files  # noqa: E402
k = json.load(open("campaign/permeability.json"))
print("\n== main job: simple-cubic spheres, c = 0.125, one 6 rc cell (12^3 voxels of 0.5 rc), axis x ==")
ax = k["axes"]["x"]
if not ax.get("k_defined"):
    print(f"mDPD: no Darcy range: k is not defined by these runs ({ax.get('k_undefined_why')})")
    sys.exit(0)
kr, ke = ax["k_rc2"], ax["k_rc2_err"]
print(f"mDPD (mdpore permeability): k = {kr:.4g} +- {ke:.2g} rc^2 = {ax['k_m2']:.3g} m^2 = "
      f"{ax['k_nD']:.3g} +- {ax['k_nD_err']:.2g} nD (Darcy range; {k['convention']})")
zh = 0.03985 * 6.0 ** 2
print(f"Zick & Homsy (smooth spheres): k = {zh:.4g} rc^2; mDPD / ZH = {kr / zh:.3f}")
if sys.argv[1]:
    k1, k2, kf = foam_k_files(sys.argv[1], "foam_r2.json", 0.5)
    print(f"OpenFOAM on the same voxels (staircase): k = {kf:.4g} rc^2 (voxel mesh {k1:.4g}, refined 2x {k2:.4g}, "
          f"extrapolated); mDPD / foam = {kr / kf:.3f}")
PY

# 2. A real rock: a 16^3 crop of a Berea sandstone micro-CT image (cases/rock, 5.345 um voxels).
# It is not periodic, so the campaign mirrors it along the flow axis (boundary auto), chooses the
# voxel edge in rc from its critical throat (resolution auto), leaves out runs whose liquid heated,
# cavitated or was compressed, and reports k only where a Darcy range exists (exit 3 otherwise).
# foam solves the same voxels with the same faces (--boundary mirror --sides periodic) on the voxel
# mesh and refined 2x, extrapolated to the voxels' continuum limit.
set +e
"$m" permeability "$root/cases/rock/berea16.raw" --axis x --np "$np" --workdir rock "$@" > rock.log 2>&1
rock_rc=$?
set -e
grep -E "boundary along x|rc per voxel|scale:|left out|Darcy range|k_xx|no Darcy range" rock.log || true
[ "$rock_rc" -eq 0 ] || [ "$rock_rc" -eq 3 ] || { tail -20 rock.log; echo "mdpore permeability (rock) failed (exit $rock_rc)"; exit 1; }
rfoam=""
if "$m" foam "$root/cases/rock/berea16.raw" --axis x --boundary mirror --sides periodic > rock_foam.json 2> rock_foam.log &&
   "$m" foam "$root/cases/rock/berea16.raw" --axis x --boundary mirror --sides periodic --refine 2 > rock_foam_r2.json 2>> rock_foam.log; then
  rfoam=rock_foam.json
else
  echo "mdpore foam: not run ($(tail -1 rock_foam.log)); the OpenFOAM comparison is skipped"
fi
python3 - "$rfoam" "$root" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2] + "/validation/permeability")
from sphere_array import foam_k_files  # noqa: E402
k = json.load(open("rock/permeability.json"))
ax, a = k["axes"]["x"], k["rc_per_voxel"]
print("\n== main job: a real rock, Berea sandstone 16^3 crop (cases/rock/berea16.raw), axis x ==")
print(f"boundary: faces {k['boundary']['x']['faces']} (seam continuity {k['boundary']['x']['seam_continuity']:.2f}), "
      f"sides {k['boundary']['sides']}; resolution: {a:g} rc per voxel ({k['resolution']['rc_per_voxel_source']}); "
      f"rc = {k['units']['rc_m']:.3g} m, {k['resolution'].get('regime', '?')} regime")
for r in ax.get("left_out", []):
    print(f"left out: G = {r['G']:.4g}: {r['why']}")
if not ax.get("k_defined"):
    print(f"mDPD: no Darcy range: k is not defined by these runs ({ax.get('k_undefined_why')})")
    sys.exit(0)
kr, ke = ax["k_rc2"], ax["k_rc2_err"]
mD = ax["k_m2"] / 9.869233e-16
print(f"mDPD (mdpore permeability): k = {kr:.4g} +- {ke:.2g} rc^2 = {kr / a**2:.4g} voxel^2 = {ax['k_m2']:.3g} m^2 = "
      f"{mD:.4g} mD (Darcy range; {k['convention']})")
if sys.argv[1]:
    k1, k2, kf = foam_k_files(sys.argv[1], "rock_foam_r2.json", a)
    print(f"OpenFOAM, same voxels and faces: k = {kf:.4g} rc^2 (voxel mesh {k1:.4g}, refined 2x {k2:.4g}, "
          f"extrapolated); mDPD / foam = {kr / kf:.3f}")
PY

# 3. The end-to-end coupled demo (docs/coupling.md): a layered sample, the sphere array above next
# to a denser one (c = 0.3) along x, cut into 2 x 1 x 1 blocks; a campaign per block, the fitted
# laws in the continuum solve, the block gradients fed back until two passes agree, and the
# sample's k_eff with its error, next to OpenFOAM on the whole layered image. The runs use the GPU
# when there is one (mdpore run --backend auto), else the CPU.
"$m" image make spheres --cell 12 --c 0.3 --cells 1 -o spheres_c0.3.h5 > /dev/null
"$m" image stack spheres_c0.125.h5 spheres_c0.3.h5 --axis x -o layered.h5 > /dev/null
cat > couple.yaml <<YAML
image: layered.h5
blocks: [2, 1, 1]
axis: x
workdir: couple
campaign: {np: $np, mpiexec: "mpiexec --oversubscribe"}
YAML
set +e
"$m" couple couple.yaml
couple_rc=$?
set -e
[ "$couple_rc" -eq 0 ] || [ "$couple_rc" -eq 4 ] || { echo "mdpore couple failed (exit $couple_rc)"; exit 1; }
foam2=""
if "$m" foam layered.h5 --axis x > foam_layered.json 2> foam_layered.log &&
   "$m" foam layered.h5 --axis x --refine 2 > foam_layered_r2.json 2>> foam_layered.log; then
  foam2=foam_layered.json
fi
python3 - "$foam2" "$root" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2] + "/validation/permeability")
from sphere_array import foam_k_files  # noqa: E402
s = json.load(open("couple/couple.json"))
k = s["effective_permeability"]
print("\n== coupled demo: layered sample (sphere arrays c = 0.125 | c = 0.3 along x), 2 x 1 x 1 blocks ==")
for b in s["blocks_final"]:
    print(f"block {b['index']}: k = {b['k_darcy_rc2']:.4g} +- {b['k_darcy_rc2_err']:.2g} rc^2 ({b['law']}; fit chose "
          f"{b['chosen_law']}), G seen {b['G_seen']:.3g} in calibrated [{b['calibrated_G'][0]:.3g}, "
          f"{b['calibrated_G'][1]:.3g}]")
print(f"loop: {s['stop_reason']}")
print(f"k_eff (mDPD blocks -> continuum) = {k['k_rc2']:.4g} +- {k['k_rc2_err']:.2g} rc^2 = {k['k_m2']:.3g} m^2 = "
      f"{k['k_nD']:.3g} +- {k['k_nD_err']:.2g} nD (superficial velocity q = Q / A_total)")
if sys.argv[1]:
    k1, k2, kf = foam_k_files(sys.argv[1], "foam_layered_r2.json", 0.5)
    print(f"OpenFOAM on the whole layered image: k = {kf:.4g} rc^2 (voxel mesh {k1:.4g}, refined 2x {k2:.4g}, "
          f"extrapolated); loop / foam = {k['k_rc2'] / kf:.3f}")
PY
