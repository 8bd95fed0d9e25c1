#!/usr/bin/env bash
# Mesh to SDF at N^3 with default properties: `lvdif mesh-to-sdf` against the
# ParaView plugin in pvpython (Apps/ParaViewPlugin/Testing/bench_mesh_to_sdf.py),
# run one after the other, each timed by /usr/bin/time -v (wall, peak RSS).
# Prints a Markdown table for docs/BENCHMARKS.md ("Mesh to SDF in pvpython").
# Usage: scripts/bench-paraview-mesh-to-sdf.sh [N (512)] [MESH (Data/extracted/bunny00.off)] [ROUNDS (2)]
# Env: LVDIF_CLI (default build/bin/lvdif), PV_BUILD_DIR (default build-pv),
#      BENCH_NO_BAND=1 adds a pvpython run with Band Width 0 (the plugin's former default).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
N="${1:-512}"
MESH="${2:-$here/Data/extracted/bunny00.off}"
ROUNDS="${3:-2}"
CLI="${LVDIF_CLI:-$here/build/bin/lvdif}"
SHIM="${LVDIF_PVSHIM:-/opt/lvdif-pvshim}"
[ -x "$CLI" ] || { echo "bench: no CLI at $CLI (build it, or set LVDIF_CLI)" >&2; exit 1; }
[ -f "$MESH" ] || { echo "bench: no mesh $MESH (scripts/extract-meshes.sh)" >&2; exit 1; }
plugin=$("$here/scripts/build-paraview-plugin.sh" "${PV_BUILD_DIR:-$here/build-pv}" "$SHIM" | tail -n1)
export LVDIF_PV_PYTHONPATH="$SHIM/pvpy/usr/lib/python3/dist-packages"
export PYTHONPATH="$here/Apps/ParaViewPlugin/Testing:$here/Testing/Support:$LVDIF_PV_PYTHONPATH"
export VTK_SMP_BACKEND_IN_USE="${VTK_SMP_BACKEND_IN_USE:-STDThread}"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# wall seconds and peak RSS (MiB) of one /usr/bin/time -v log
measure() {
  local wall rss
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n=split($2,t,":"); s=0; for(i=1;i<=n;i++) s=s*60+t[i]; print s}' "$1")
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2/1024}' "$1")
  echo "$wall $rss"
}

echo "machine: $(nproc --all) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(free -g | awk '/Mem:/ {print $2}') GiB," \
  "OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}, VTK_SMP_BACKEND_IN_USE=$VTK_SMP_BACKEND_IN_USE, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "mesh: $(basename "$MESH"), grid: longest axis $N points, defaults (winding number, band 8, padding 2)"
echo
echo "| round | run | Mesh to SDF (s) | process wall (s) | peak RSS (MiB) | pvpython / CLI (process wall) |"
echo "|---|---|---|---|---|---|"
for r in $(seq "$ROUNDS"); do
  /usr/bin/time -v "$CLI" mesh-to-sdf "$MESH" "$tmp/out.lvdv" --dims "$N" >"$tmp/cli.out" 2>"$tmp/cli.time"
  read -r cwall crss <<<"$(measure "$tmp/cli.time")"
  echo "| $r | \`lvdif mesh-to-sdf --dims $N\` (writes .lvdv) | - | $cwall | $crss | |"
  runs=("")
  [ "${BENCH_NO_BAND:-0}" = 1 ] && [ "$r" = 1 ] && runs+=("0")
  for pvband in "${runs[@]}"; do
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" /usr/bin/time -v "$SHIM/pvpy/usr/bin/pvpython3.11" --force-offscreen-rendering \
      "$here/Apps/ParaViewPlugin/Testing/bench_mesh_to_sdf.py" "$plugin" "$MESH" "$N" $pvband >"$tmp/pv.out" 2>"$tmp/pv.time" \
      || { cat "$tmp/pv.out" "$tmp/pv.time" >&2; exit 1; }
    read -r pwall prss <<<"$(measure "$tmp/pv.time")"
    line=$(grep '^BENCH' "$tmp/pv.out")
    eval "$(echo "${line#BENCH }" | tr ' ' ';')"
    what="pvpython MeshToSDF(MaxDimension=$N), BandWidth $band"
    ratio=$(awk -v a="$pwall" -v b="$cwall" 'BEGIN {printf "%.2f", a / b}')
    echo "| $r | $what, grid $dims | $sdf_s | $pwall | $prss | $ratio |"
    [ -z "$pvband" ] && { echo "$ratio" >>"$tmp/ratios"; echo "$cwall" >>"$tmp/cli"; echo "$pwall" >>"$tmp/pv"; }
  done
done
# the machine's speed drifts between runs: the median of the paired ratios, and best against best
median() { sort -g "$1" | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
echo
echo "median pvpython / CLI (paired, default properties): $(median "$tmp/ratios"); best pvpython $(sort -g "$tmp/pv" | head -1) s / best CLI $(sort -g "$tmp/cli" | head -1) s = $(awk -v a="$(sort -g "$tmp/pv" | head -1)" -v b="$(sort -g "$tmp/cli" | head -1)" 'BEGIN {printf "%.2f", a / b}')"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
