#!/bin/sh
# Wall time to a permeability on one GPU: the same campaign with its runs one after another
# (--jobs 1) and at once (--jobs auto: as many as fit in the GPU's free memory), for a periodic
# sphere array at three resolutions (about 6e4, 6e5 and 6e6 particles per run). Prints per size and
# mode the campaign's wall time, its particle-steps per second, the GPU's mean utilisation (nvidia-smi
# sampled every 0.5 s) and k +- err, then the ratio of the wall times measured in the same call.
# Each mode has its own --workdir (no run reused); the wall-patch database of each resolution is built
# once by a warm-up campaign of 20-step runs, so neither mode pays for it.
# usage: sh bench/campaign_concurrency.sh MDPORE [OUT_DIR]
set -u
M=$1
W=${2:-/tmp/campaign_concurrency}
rm -rf "$W" && mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR="$W/cache"
mkdir -p "$MDPORE_CACHE_DIR"
"$M" image make spheres --cell 24 --c 0.4 -o spheres24.raw > /dev/null || exit 1
git -C "$(dirname "$0")" rev-parse --short HEAD 2> /dev/null
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader 2> /dev/null

# one campaign; prints: wall seconds, particle-steps, mean GPU utilisation, k, err
campaign() { # RC STEPS JOBS TAG
  nvidia-smi --query-gpu=utilization.gpu --format=csv,noheader,nounits -lms 500 > "util_$4.txt" 2> /dev/null &
  smi=$!
  t0=$(date +%s.%N)
  "$M" permeability spheres24.raw --axis x --rc-per-voxel "$1" --max-steps "$2" --jobs "$3" \
    --workdir "wd_$4" > "out_$4.txt" 2> "err_$4.txt"
  rc=$?
  t1=$(date +%s.%N)
  kill "$smi" 2> /dev/null
  wait "$smi" 2> /dev/null
  python3 - "$4" "$t0" "$t1" "$rc" << 'EOF'
import glob, json, sys
tag, t0, t1, rc = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
psteps = 0
for s in glob.glob(f"wd_{tag}/runs/*/summary.json"):
    j = json.load(open(s))
    psteps += j["timing"]["particles"] * j["timing"]["steps"]
util = [float(x) for x in open(f"util_{tag}.txt").read().split() if x.replace(".", "").isdigit()]
k = err = None
try:
    p = json.load(open(f"wd_{tag}/permeability.json"))
    ax = p["axes"]["x"]
    k, err = ax.get("k_rc2"), ax.get("k_rc2_err")
except Exception:
    pass
wall = t1 - t0
print(f"{tag:12s} exit {rc}  wall {wall:8.1f} s  {psteps / wall:10.3e} particle-steps/s  "
      f"GPU util {sum(util) / max(len(util), 1):5.1f}% ({len(util)} samples)  k {k} +- {err}")
open(f"wall_{tag}.txt", "w").write(f"{wall}\n")
EOF
}

# BENCH_SIZES: "RC_PER_VOXEL STEPS TAG;..." to override the three sizes
echo "${BENCH_SIZES:-1 6000 s60k;2.15 6000 s600k;4.64 3000 s6M}" | tr ';' '\n' | while read -r size; do
  set -- $size
  "$M" permeability spheres24.raw --axis x --rc-per-voxel "$1" --max-steps 20 --workdir "warm_$3" \
    > /dev/null 2> "warm_$3.txt"
  grep -h "particles per run" "warm_$3.txt" | head -1
  campaign "$1" "$2" 1 "$3_seq"
  campaign "$1" "$2" auto "$3_conc"
  python3 -c "s=float(open('wall_$3_seq.txt').read()); c=float(open('wall_$3_conc.txt').read()); print(f'$3: sequential / concurrent wall time = {s / c:.2f}')"
  grep -h "runs at once" "err_$3_conc.txt" | head -1
done
