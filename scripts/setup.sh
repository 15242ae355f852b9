#!/usr/bin/env bash
# Installs the Debian packages mdpore builds and tests with. Safe to run again (apt-get is idempotent).
# Set MDPORE_SKIP_SETUP=1 to skip (e.g. on a machine without root where the packages are already there).
set -euo pipefail
[ "${MDPORE_SKIP_SETUP:-0}" = "1" ] && exit 0
pkgs=(build-essential cmake pkg-config clang-format
      libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools
      libyaml-dev librandom123-dev libtiff-dev petsc-dev
      python3 python3-numpy python3-matplotlib python3-yaml python3-h5py
      openfoam)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" != "0" ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
