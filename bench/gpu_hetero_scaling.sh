#!/bin/sh
# Several GPUs on the heterogeneous image: bench/balance.py's image (x < half a
# dense pack of porosity 0.30, x >= half open pores of porosity 0.85; 0.5 rc voxels, 128 x 128
# voxels across), uniform cuts against cost cuts (the weight imbalance each gives is printed).
# Strong scaling: NX_STRONG voxels along x on 1 GPU, then on 2 and 4. Weak scaling: NX_STRONG
# voxels per GPU (the image grows along x with the GPUs). Needs python3 with numpy (makes images).
# usage: bench/gpu_hetero_scaling.sh MDPORE OUTDIR   (NX_STRONG default 640: ~9M particles)
set -u
M=$1; O=$2; mkdir -p "$O"
NX=${NX_STRONG:-640}
G=$(nvidia-smi -L | wc -l)
export MDPORE="$M"
bal() { # bal NAME ARGS...
  name=$1; shift
  echo "== $name: balance.py $*"
  python3 bench/balance.py --backend cuda --ny 128 --nz 128 --steps 400 --workdir "$O/$name" "$@" \
    2>&1 | grep -v "^    "
}
bal strong_np2 --np 2 --nx "$NX" --one-rank
[ "$G" -ge 4 ] && bal strong_np4 --np 4 --nx "$NX"
bal weak_np2 --np 2 --nx $((2 * NX))
[ "$G" -ge 4 ] && bal weak_np4 --np 4 --nx $((4 * NX))
exit 0
