#!/bin/sh
# A/B check of a change on the GPU machine, in one call: builds the tree it is run from (B) and an
# older source tree (A, e.g. `git archive <commit> | tar -x -C DIR`), runs the CUDA tests of B, runs
# the same scenes for 300 steps on A (twice) and B with the CUDA backend (1 rank, and 2 ranks sharing
# the GPU) and prints T and p at steps 50 and 300 of each (GPU runs do not repeat bitwise: the
# neighbour-list order varies between runs, so A vs A shows the spread to expect), then times
# `gpu_bench porous 72` alternately A, B, A, B (same run: the ratio is meaningful).
# usage: bench/gpu_ab.sh A_SRC_DIR SCENE_DIR [OUTDIR]   (SCENE_DIR: *.yaml, 300 steps, thermo every 50)
# Needs CMake, nvcc, MPI, HDF5 (h5diff), libyaml and Random123 (RANDOM123_ROOT, PKG_CONFIG_PATH).
set -u
A=$1; S=$2; O=${3:-gpu-ab}; mkdir -p "$O"
B=$(cd "$(dirname "$0")/.." && pwd)
flags="-DCMAKE_BUILD_TYPE=Release -DMDPORE_CUDA=ON -DMDPORE_PETSC=OFF -DMDPORE_TIFF=OFF -DMDPORE_OPENFOAM_TESTS=OFF"
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$O/gpu.txt"
(cmake -S "$A" -B /tmp/build-a $flags > "$O/build-a.log" 2>&1 &&
 cmake --build /tmp/build-a -j 16 --target mdpore gpu_bench >> "$O/build-a.log" 2>&1) &
cmake -S "$B" -B /tmp/build-b $flags > "$O/build-b.log" 2>&1 && cmake --build /tmp/build-b -j 16 >> "$O/build-b.log" 2>&1
wait
for x in a b; do [ -x /tmp/build-$x/bin/mdpore ] || { echo "build $x failed"; tail -30 "$O/build-$x.log"; exit 1; }; done
grep -c "warning" "$O/build-b.log" | sed 's/^/compiler warnings in B: /'
(cd /tmp/build-b && ctest -L cuda --output-on-failure --timeout 300) > "$O/tests.log" 2>&1
grep -E "tests passed|Failed|FAIL|after 5 steps|agree|T cpu" "$O/tests.log" | head -20
for s in "$S"/*.yaml; do
  n=$(basename "$s" .yaml)
  for np in 1 2; do
    for x in a a2 b; do
      mpiexec -n $np /tmp/build-${x%2}/bin/mdpore run --backend cuda --output-dir "/tmp/run-$x-$n-$np" "$s" \
        > "$O/run-$x-$n-$np.log" 2>&1 || echo "run $x $n np$np failed: $(tail -2 "$O/run-$x-$n-$np.log")"
    done
    for x in a a2 b; do
      printf "cuda %s np%s %-2s thermo at steps 50 and 300 (step,T,p): " $n $np $x
      grep -E "^(50|300)," "/tmp/run-$x-$n-$np/thermo.csv" | cut -d, -f1,3,11 | tr '\n' ' '; echo
    done
  done
done
for rep in 1 2; do
  for x in a b; do
    printf "%s rep%s: " $x $rep; /tmp/build-$x/bin/gpu_bench porous 72 100 50 cuda 2>&1 | grep -v "backend cuda on" | tail -1
  done
done | tee "$O/bench.txt"
