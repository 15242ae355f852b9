#!/usr/bin/env bash
# The accuracy-vs-time ladders on the GPU machine (1 GPU + 16 cores), one call of
# at most ~9 minutes. Run from the repository root after building there:
#
#   validation/accuracy/run_gpu.sh BUILD_DIR [DOUBLE_BUILD_DIR]
#
# 1. the GPU ladder (--backend cuda; the reference run first) for ACC_GPU_BUDGET seconds (default 330);
# 2. a CPU ladder (--backend cpu --np 4, OMP_NUM_THREADS=4, a 2^3-cell image, no reference run of its
#    own: the report compares it with the GPU reference) for ACC_CPU_BUDGET seconds (default 150);
# 3. the report (validation/accuracy/accuracy_knobs.py --report): $OUT/results.tar.gz (accuracy.md
#    and the PNGs; one file, as few files come back from a device call), $OUT/accuracy_*.json and
#    $OUT/ladders.log. `--report --out DIR_WITH_THE_JSON` remakes the plots anywhere.
# The runs and the JSON files live in ACC_WORK (default /tmp/mdpore-accuracy, kept while the machine
# stays warm); a fresh machine starts from validation/accuracy/results/accuracy_*.json when present
# (copy the JSON files that came back there), so repeated calls fill the ladders in.
# DOUBLE_BUILD_DIR (optional): a build with -DMDPORE_DOUBLE=ON for the precision knob (the pair math
# type is a build-time switch); when DOUBLE_BUILD_DIR/bin/mdpore is missing the script configures and
# builds it there first (~30 s on 16 cores; cmake flags from ACC_CMAKE_FLAGS, default below; the
# environment must find libyaml etc. as for the main build).
# ACC_KNOBS limits the knobs (comma list, default all); ACC_SKIP_CPU=1 / ACC_SKIP_GPU=1 skip a pass.
set -euo pipefail
BUILD=${1:?usage: run_gpu.sh BUILD_DIR [DOUBLE_BUILD_DIR]}
DOUBLE=${2:-}
OUT=${OUT:-$PWD/out/accuracy}
WORK=${ACC_WORK:-/tmp/mdpore-accuracy}
PY=${PYTHON:-python3}
SCRIPT=validation/accuracy/accuracy_knobs.py
KNOBS=${ACC_KNOBS:-dt,precision,resolution,window,skin,wall_density,boundary,forcing,cells}
mkdir -p "$OUT" "$WORK"
for be in cuda cpu; do
  if [ ! -f "$WORK/accuracy_$be.json" ] && [ -f "validation/accuracy/results/accuracy_$be.json" ]; then
    cp "validation/accuracy/results/accuracy_$be.json" "$WORK/"
  fi
done
PREC=()
if [ -n "$DOUBLE" ]; then
  if [ ! -x "$DOUBLE/bin/mdpore" ]; then
    flags=${ACC_CMAKE_FLAGS:--DMDPORE_CUDA=ON -DMDPORE_PETSC=OFF -DMDPORE_TIFF=OFF -DMDPORE_OPENFOAM_TESTS=OFF}
    # shellcheck disable=SC2086
    { cmake -S . -B "$DOUBLE" -DCMAKE_BUILD_TYPE=Release $flags -DMDPORE_DOUBLE=ON &&
      cmake --build "$DOUBLE" -j "$(nproc)" --target mdpore; } > "$WORK/double_build.log" 2>&1 ||
      { echo "run_gpu.sh: the double build failed (tail of $WORK/double_build.log):" >&2;
        tail -20 "$WORK/double_build.log" >&2; }
  fi
  if [ -x "$DOUBLE/bin/mdpore" ]; then
    PREC=(--precision-binaries "double=$DOUBLE/bin/mdpore")
  else
    echo "run_gpu.sh: no $DOUBLE/bin/mdpore: the precision knob measures the default binary only" >&2
  fi
fi
if [ "${ACC_SKIP_GPU:-0}" != 1 ]; then
  nvidia-smi --query-gpu=name,memory.total --format=csv,noheader >> "$OUT/ladders.log" 2>&1 || true
  "$PY" "$SCRIPT" --backend cuda --mdpore "$BUILD/bin/mdpore" "${PREC[@]}" --out "$WORK" \
    --knobs "$KNOBS" --budget-seconds "${ACC_GPU_BUDGET:-330}" 2>&1 | tee -a "$OUT/ladders.log"
fi
if [ "${ACC_SKIP_CPU:-0}" != 1 ]; then
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-4} "$PY" "$SCRIPT" --backend cpu --np "${ACC_NP:-4}" \
    --mdpore "$BUILD/bin/mdpore" --cells "${ACC_CPU_CELLS:-2}" --no-reference --out "$WORK" \
    --knobs "$KNOBS" --budget-seconds "${ACC_CPU_BUDGET:-150}" 2>&1 | tee -a "$OUT/ladders.log"
fi
cp "$WORK"/accuracy_*.json "$OUT/" 2>/dev/null || true
rm -rf "$WORK/results"
"$PY" "$SCRIPT" --report --out "$WORK" --results "$WORK/results" 2>&1 | tee -a "$OUT/ladders.log" || true
tar -czf "$OUT/results.tar.gz" -C "$WORK" results 2>/dev/null || true
