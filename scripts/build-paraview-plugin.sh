#!/usr/bin/env bash
# Builds the LVDIF ParaView plugin in a second build tree, against Debian's
# ParaView 5.11 (its own VTK 9.2), through the route-B shim prefix.
#
# Usage: scripts/build-paraview-plugin.sh [BUILD_DIR] [SHIM_PREFIX]
#   BUILD_DIR    default <repo>/build-pv
#   SHIM_PREFIX  default /opt/lvdif-pvshim (see scripts/paraview-shim.sh)
# Env: JOBS (default 2), extra cmake args in LVDIF_PV_CMAKE_ARGS.
# Prints the path of the built plugin (LVDIF.so) on its last line.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B="${1:-$here/build-pv}"
SHIM="${2:-/opt/lvdif-pvshim}"
JOBS="${JOBS:-2}"

mkdir -p "$B"
pvdir=$("$here/scripts/paraview-shim.sh" "$SHIM" | tail -n1)
# The main build's CUDA kernels are not needed in ParaView (the filters fall
# back to the CPU); the plugin tree builds no apps, benchmarks or Core tests.
cmake -S "$here" -B "$B" -DLVDIF_PARAVIEW_PLUGIN=ON -DParaView_DIR="$pvdir" \
  -DLVDIF_CUDA="${LVDIF_PV_CUDA:-OFF}" -DLVDIF_BUILD_BENCHMARKS=OFF -DLVDIF_BUILD_APPS=OFF \
  -DBUILD_TESTING=ON ${LVDIF_PV_CMAKE_ARGS:-} >"$B/lvdif-configure.log" 2>&1 \
  || { cat "$B/lvdif-configure.log" >&2; exit 1; }
cmake --build "$B" --target LVDIF -j "$JOBS" >"$B/lvdif-build.log" 2>&1 \
  || { tail -n 80 "$B/lvdif-build.log" >&2; exit 1; }
plugin=$(cat "$B/lvdif-plugin-path.txt")
[ -f "$plugin" ] || { echo "build-paraview-plugin: $plugin was not built" >&2; exit 1; }
echo "$plugin"
