#!/usr/bin/env bash
# The main job, one command on a fresh machine: installs what is needed, builds everything, then runs
# a small permeability campaign (docs/permeability.md) on an image mdpore makes itself: a simple-cubic
# array of spheres at solid fraction 0.125 (12^3 voxels of 0.5 rc: one 6 rc cell), flow along x.
# It prints k from the mDPD runs (rc^2, m^2, nD; superficial-velocity convention) with its error,
# OpenFOAM's k on the SAME voxels (`mdpore foam`, when OpenFOAM is installed) and Zick & Homsy's
# value for the smooth spheres. The coupled continuum/pore-scale demo does not exist yet (issue 12).
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
"$m" image make spheres --cell 12 --c 0.125 --cells 1 -o spheres_c0.125.h5 > image.json
np=$(( $(nproc) >= 2 ? 2 : 1 ))
"$m" permeability spheres_c0.125.h5 --axis x --np "$np" --workdir campaign "$@"
foam=""
if "$m" foam spheres_c0.125.h5 --axis x > foam.json 2> foam.log; then
  foam=foam.json
else
  echo "mdpore foam: not run ($(tail -1 foam.log)); the OpenFOAM comparison is skipped"
fi
python3 - "$foam" <<'PY'
import json, sys
k = json.load(open("campaign/permeability.json"))
print("\n== main job: simple-cubic spheres, c = 0.125, one 6 rc cell (12^3 voxels of 0.5 rc), axis x ==")
ax = k["axes"]["x"]
kr, ke = ax["k_rc2"], ax["k_rc2_err"]
print(f"mDPD (mdpore permeability): k = {kr:.4g} +- {ke:.2g} rc^2 = {ax['k_m2']:.3g} m^2 = "
      f"{ax['k_nD']:.3g} +- {ax['k_nD_err']:.2g} nD (Darcy fit; {k['convention']})")
zh = 0.03985 * 6.0 ** 2
print(f"Zick & Homsy (smooth spheres): k = {zh:.4g} rc^2; mDPD / ZH = {kr / zh:.3f}")
if sys.argv[1]:
    f = json.load(open(sys.argv[1]))
    kf = f["permeability_voxel2"] * 0.5 ** 2
    print(f"OpenFOAM on the same voxels (staircase): k = {kf:.4g} rc^2; mDPD / foam = {kr / kf:.3f}")
PY
