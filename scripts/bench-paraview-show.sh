#!/bin/bash
# Peak RSS of pvpython opening the n^3 dice (.lvdv, the sparse volume) and
# showing it with the default representation (outline), under /usr/bin/time -v.
# Usage: scripts/bench-paraview-show.sh [N] [PLUGIN_BUILD_DIR] [LVDIF]
#   N default 1024; PLUGIN_BUILD_DIR default build-pv; LVDIF (the CLI that
#   makes the dice file) default build/bin/lvdif. Needs an X server (DISPLAY;
#   Xvfb) as every pvpython run here.
set -euo pipefail
N=${1:-1024}
here=$(cd "$(dirname "$0")/.." && pwd)
B=${2:-$here/build-pv}
CLI=${3:-$here/build/bin/lvdif}
tmp=${TMPDIR:-/tmp}/lvdif-bench-sparse-$N
mkdir -p "$tmp"
sed "s/^n = 128/n = $N/" "$here/Data/scripts/dice.lvs" > "$tmp/dice.lvs"
[ -f "$tmp/dice.lvdv" ] || "$CLI" script "$tmp/dice.lvs" --out "$tmp/dice.lvdv" > /dev/null
PV=/opt/lvdif-pvshim/pvpy/usr/lib/python3/dist-packages
export LVDIF_PV_PYTHONPATH=$PV PYTHONPATH="$here/Apps/ParaViewPlugin/Testing:$here/Testing/Support:$PV" VTK_SMP_BACKEND_IN_USE=STDThread
/usr/bin/time -v /opt/lvdif-pvshim/pvpy/usr/bin/pvpython3.11 --force-offscreen-rendering \
  "$here/Apps/ParaViewPlugin/Testing/bench_show_volume.py" "$(cat "$B/lvdif-plugin-path.txt")" "$tmp/dice.lvdv" \
  > "$tmp/show.out" 2> "$tmp/show.time"
cat "$tmp/show.out"
echo "dice ${N}^3 ($(du -h "$tmp/dice.lvdv" | cut -f1)), $(nproc) cores: wall $(grep 'Elapsed (wall clock)' "$tmp/show.time" | awk '{print $NF}'), peak RSS $(grep 'Maximum resident set size' "$tmp/show.time" | awk '{printf "%.0f", $NF/1024}') MiB"
