#!/bin/sh
# Wall time to a permeability on one GPU: the same campaign of 5 runs with its runs one after
# another (--jobs 1: "seq"), at once as processes (--jobs auto: as many as fit in the GPU's free
# memory: "conc") and at once as replicas stepped in one process (--jobs auto --job-mode replicas:
# "rep"), for a periodic sphere array (by default about 6e4 and 6e5 particles per run). Prints per
# size and mode the campaign's wall time, its particle-steps per second, the GPU's mean utilisation
# (nvidia-smi sampled every 0.5 s) and k +- err, then the ratios of the wall times measured in the
# same call and whether every run's flux.csv is the same bytes in every mode.
# Each mode has its own --workdir (no run reused); the wall-patch database of each resolution is
# built once by a warm-up campaign of 20-step runs, so no mode pays for it.
# usage: sh bench/campaign_concurrency.sh [MDPORE [OUT_DIR]]
#   MDPORE: the binary (default: $MDPORE); OUT_DIR: default campaign_concurrency_out in the current
#   folder. BENCH_SIZES="RC_PER_VOXEL STEPS TAG;..." overrides the sizes (6e6 particles per run:
#   "4.64 3000 s6M"); BENCH_MODES="seq conc rep" chooses the modes (the first is the reference).
set -u
M=${1:-${MDPORE:-}}
[ -n "$M" ] || {
  echo "usage: sh bench/campaign_concurrency.sh MDPORE [OUT_DIR] (or set MDPORE)" >&2
  exit 2
}
case "$M" in /*) ;; *) M="$(pwd)/$M" ;; esac
W=${2:-campaign_concurrency_out}
MODES=${BENCH_MODES:-seq conc rep}
git -C "$(dirname "$0")" rev-parse --short HEAD 2> /dev/null
rm -rf "$W" && mkdir -p "$W" && cd "$W" || exit 1
export MDPORE_CACHE_DIR="$(pwd)/cache"
mkdir -p "$MDPORE_CACHE_DIR"
"$M" image make spheres --cell 24 --c 0.4 -o spheres24.raw > /dev/null || exit 1
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader 2> /dev/null

# one campaign; prints: wall seconds, particle-steps, mean GPU utilisation, k, err
campaign() { # RC STEPS JOBS TAG [MORE OPTIONS]
  rc_v=$1 steps=$2 jobs=$3 tag=$4
  shift 4
  nvidia-smi --query-gpu=utilization.gpu --format=csv,noheader,nounits -lms 500 > "util_$tag.txt" 2> /dev/null &
  smi=$!
  t0=$(date +%s.%N)
  "$M" permeability spheres24.raw --axis x --rc-per-voxel "$rc_v" --max-steps "$steps" \
    --jobs "$jobs" --workdir "wd_$tag" "$@" > "out_$tag.txt" 2> "err_$tag.txt"
  rc=$?
  t1=$(date +%s.%N)
  kill "$smi" 2> /dev/null
  wait "$smi" 2> /dev/null
  python3 - "$tag" "$t0" "$t1" "$rc" << 'EOF'
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

echo "${BENCH_SIZES:-1 6000 s60k;2.15 6000 s600k}" | tr ';' '\n' | while read -r size; do
  set -- $size
  "$M" permeability spheres24.raw --axis x --rc-per-voxel "$1" --max-steps 20 --workdir "warm_$3" \
    > /dev/null 2> "warm_$3.txt"
  grep -h "particles per run" "warm_$3.txt" | head -1
  for mode in $MODES; do
    case $mode in
      seq) campaign "$1" "$2" 1 "$3_seq" ;;
      conc) campaign "$1" "$2" auto "$3_conc" ;;
      rep) campaign "$1" "$2" auto "$3_rep" --job-mode replicas ;;
      *) echo "BENCH_MODES: unknown mode '$mode' (expected seq, conc or rep)" >&2 ;;
    esac
  done
  python3 - "$3" $MODES << 'EOF'
import filecmp, glob, os, sys
size, modes = sys.argv[1], sys.argv[2:]
wall = {m: float(open(f"wall_{size}_{m}.txt").read()) for m in modes}
for i, a in enumerate(modes):
    for b in modes[i + 1:]:
        print(f"{size}: wall time {a} / {b} = {wall[a] / wall[b]:.2f}")
def runs(mode):  # each run's flux.csv by its body force (the folders' names hash their paths)
    out = {}
    for d in glob.glob(f"wd_{size}_{mode}/runs/*/"):
        key = [l.strip() for l in open(d + "scene.yaml") if "body_force" in l or "liquid: [" in l]
        out[tuple(key)] = d + "flux.csv"
    return out
ref = runs(modes[0])
other = [runs(m) for m in modes[1:]]
same = sum(all(k in o and os.path.exists(f) and os.path.exists(o[k]) and
               filecmp.cmp(f, o[k], shallow=False) for o in other) for k, f in ref.items())
print(f"{size}: flux.csv the same bytes in every mode: {same} of {len(ref)} runs")
EOF
  grep -h -e "--jobs auto:" -e "in one process" err_"$3"_*.txt 2> /dev/null | sort -u
done
