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
# plus --force-offscreen-rendering (the tests pass it). Our own Xvfb, on a
# display it picks itself (-displayfd: no race with other xvfb-run -a users,
# which gave "bad X server connection" aborts when several ran at once), and
# -noreset: by default an X server resets when its last client leaves, and a
# test that connects during that reset aborts the same way (seen between two
# pvpython tests run one after the other).
xpid=""
if [ -z "${DISPLAY:-}" ]; then
  dfile=$(mktemp)
  Xvfb -displayfd 1 -screen 0 1280x1024x24 -nolisten tcp -noreset >"$dfile" 2>/dev/null &
  xpid=$!
  trap 'kill "$xpid" 2>/dev/null; rm -f "$dfile"' EXIT
  for _ in $(seq 100); do [ -s "$dfile" ] && break; sleep 0.1; done
  [ -s "$dfile" ] || { echo "test-paraview: Xvfb did not start" >&2; exit 1; }
  export DISPLAY=":$(head -n1 "$dfile")"
fi
ctest --test-dir "$B" -L paraview --output-on-failure
