#!/usr/bin/env bash
# Sets up the route-B shim, builds the ParaView plugin (second build tree) and
# runs its tests: the pvpython pipeline/image/dialog test and the pvbatch MPI
# tests (1, 2 and 4 ranks). Exit status non-zero on any failure.
# Usage: scripts/test-paraview.sh [BUILD_DIR] [SHIM_PREFIX]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B="${1:-$here/build-pv}"
SHIM="${2:-${LVDIF_PVSHIM:-/opt/lvdif-pvshim}}"

"$here/scripts/build-paraview-plugin.sh" "$B" "$SHIM" >/dev/null
cmake "$B" >/dev/null  # the test list follows the registered XML

export VTK_SMP_BACKEND_IN_USE=STDThread OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Debian's ParaView is X/GLX only: every pvpython/pvbatch needs an X server,
# plus --force-offscreen-rendering (the tests pass it).
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir "$B" -L paraview --output-on-failure
fi
exec ctest --test-dir "$B" -L paraview --output-on-failure
