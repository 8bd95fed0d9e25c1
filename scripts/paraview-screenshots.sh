#!/usr/bin/env bash
# Takes the pictures of docs/PARAVIEW.md with pvpython (SaveScreenshot) under Xvfb.
# Uses the meshes of scripts/extract-meshes.sh when they are in Data/extracted
# (the bunny, the cow), else generated ellipsoids.
# usage: scripts/paraview-screenshots.sh [PV_BUILD_DIR (default build-pv)]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
SHIM="${LVDIF_PVSHIM:-/opt/lvdif-pvshim}"
plugin=$("$here/scripts/build-paraview-plugin.sh" "${1:-$here/build-pv}" "$SHIM" | tail -n1)
export LVDIF_PV_PYTHONPATH="$SHIM/pvpy/usr/lib/python3/dist-packages"
export PYTHONPATH="$here/Apps/ParaViewPlugin/Testing:$LVDIF_PV_PYTHONPATH"
export VTK_SMP_BACKEND_IN_USE="${VTK_SMP_BACKEND_IN_USE:-STDThread}"
xvfb-run -a -s "-screen 0 1280x1024x24" "$SHIM/pvpy/usr/bin/pvpython3.11" --force-offscreen-rendering \
  "$here/scripts/paraview_screenshots.py" "$plugin" "$here/docs/images" "$here/Data/extracted"
echo "pictures written to docs/images"
