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
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$SHIM/pvpy/usr/bin/pvpython3.11" --force-offscreen-rendering \
  "$here/scripts/paraview_screenshots.py" "$plugin" "$here/docs/images" "$here/Data/extracted"

# The GUI with the plugin (its Properties panel): ParaView itself under a private
# Xvfb, a fresh settings folder (no welcome dialog), the screen grabbed with PIL.
mesh="$here/Data/extracted/bunny00.off"
if [ -f "$mesh" ] && /usr/bin/python3 -c "import PIL.ImageGrab" 2>/dev/null; then
  home=$(mktemp -d)
  mkdir -p "$home/.config/ParaView"
  printf '[General]\nGeneralSettings.ShowWelcomeDialog=false\n' >"$home/.config/ParaView/ParaView5.11.0.ini"
  dfile=$(mktemp)
  Xvfb -displayfd 1 -screen 0 1400x900x24 -nolisten tcp -noreset >"$dfile" 2>/dev/null &
  xpid=$!
  for _ in $(seq 100); do [ -s "$dfile" ] && break; sleep 0.1; done
  display=":$(head -n1 "$dfile")"
  DISPLAY="$display" HOME="$home" PV_PLUGIN_PATH="$(dirname "$plugin")" PYTHONPATH="$LVDIF_PV_PYTHONPATH" \
    LVDIF_GUI_MESH="$mesh" paraview -geometry 1400x900+0+0 --script="$here/scripts/paraview_gui_screenshot.py" \
    >"$home/paraview.log" 2>&1 &
  pvpid=$!
  sleep "${GUI_WAIT:-30}"
  # a 256-colour palette keeps the picture under 200 KB
  /usr/bin/python3 -c "from PIL import ImageGrab; ImageGrab.grab(xdisplay='$display').convert('RGB').quantize(256).save('$here/docs/images/paraview-gui.png', optimize=True)"
  kill "$pvpid" "$xpid" 2>/dev/null || true
  rm -rf "$home" "$dfile"
else
  echo "paraview-gui.png skipped (needs Data/extracted/bunny00.off and python3-pil)"
fi
echo "pictures written to docs/images"
