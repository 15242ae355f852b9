#!/bin/sh
# Build mdpore with the CUDA backend on a bare GPU machine (the device tool's: Ubuntu, nvcc, CMake,
# Open MPI, serial HDF5; no libyaml and no Random123). The .deb files of those two are carried in
# .carry/debs (here: `mkdir -p .carry/debs && cd .carry/debs && apt-get download libyaml-0-2
# libyaml-dev librandom123-dev`) and unpacked under /opt/deps, not into /.
# usage: . bench/device_build.sh [BUILD_DIR]   (sourced: exports the paths the binaries need)
#        sets DEVICE_BUILD_OK=1 when bin/mdpore and bin/gpu_bench exist. DEVICE_TARGETS="a b ...":
#        build only those targets (include mdpore and gpu_bench).
DB_DIR=${1:-/tmp/build}
DB_SRC=$(pwd)
mkdir -p /opt/deps
for f in "$DB_SRC"/.carry/debs/*.deb; do dpkg -x "$f" /opt/deps; done
export PKG_CONFIG_PATH=/opt/deps/usr/lib/x86_64-linux-gnu/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export RANDOM123_ROOT=/opt/deps/usr
# The .pc file names /usr as its prefix: point it at the unpacked tree.
sed -i 's|^prefix=.*|prefix=/opt/deps/usr|' /opt/deps/usr/lib/x86_64-linux-gnu/pkgconfig/yaml-0.1.pc
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cmake -S "$DB_SRC" -B "$DB_DIR" -DCMAKE_BUILD_TYPE=Release -DMDPORE_CUDA=ON -DMDPORE_PETSC=OFF \
  -DMDPORE_TIFF=OFF -DMDPORE_OPENFOAM_TESTS=OFF ${DEVICE_CMAKE_FLAGS:-} > "$DB_DIR.configure.log" 2>&1 &&
  cmake --build "$DB_DIR" -j 16 ${DEVICE_TARGETS:+--target $DEVICE_TARGETS} > "$DB_DIR.build.log" 2>&1
DEVICE_BUILD_OK=0
if [ -x "$DB_DIR/bin/mdpore" ] && [ -x "$DB_DIR/bin/gpu_bench" ]; then
  DEVICE_BUILD_OK=1
  echo "device_build: built in $DB_DIR ($(grep -c 'warning' "$DB_DIR.build.log") compiler warning lines)"
else
  echo "device_build: FAILED"
  tail -30 "$DB_DIR.configure.log" "$DB_DIR.build.log"
fi
