#!/bin/sh
# The GPU benchmark set (bench/README.md): bulk mDPD fluid (rho 6.2) and the paper's
# homogeneous porous medium (physics.md section 7), each at ~2.1M and ~10M particles, one GPU.
# usage: bench/gpu_bench.sh BUILD_DIR   (prints one line per case; copy them into bench/RESULTS.md)
# Weak scaling on R GPUs: mpiexec -n R BUILD_DIR/bin/gpu_bench porous 33 100 50 (box R times longer in x).
set -e
bin=${1:-build}/bin/gpu_bench
"$bin" bulk 70 100 50      # 2,126,600 particles
"$bin" porous 33 100 50    # 2,089,791 particles (33 x 33 cells)
"$bin" bulk 118 50 50      # 10,186,798 particles
"$bin" porous 72 50 50     # 9,948,096 particles (72 x 72 cells)
