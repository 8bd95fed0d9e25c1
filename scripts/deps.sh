#!/usr/bin/env bash
# Installs, from Debian bookworm's packages, whatever the build and the tests
# need and the machine lacks. Safe to run again: it only installs what is missing.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config git
  libgtest-dev libomp-dev libzstd-dev zstd
  libvtk9-dev libvtk9-qt-dev python3-vtk9 qtbase5-dev
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libopenmesh-dev
  xvfb xauth
  openmpi-bin libopenmpi-dev
  clang libclang-rt-14-dev
  # ParaView plugin (second build tree, scripts/build-paraview-plugin.sh). Never
  # python3-paraview: it would remove libvtk9-dev; scripts/paraview-shim.sh
  # unpacks it into a private prefix instead. --no-install-recommends (below)
  # matters: paraview recommends python3-paraview.
  paraview-dev libqt5svg5-dev qtxmlpatterns5-dev-tools
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
