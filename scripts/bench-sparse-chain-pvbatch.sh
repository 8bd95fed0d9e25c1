#!/usr/bin/env bash
# The sparse chain in pvbatch, one process: MESH -> Mesh To SDF (longest axis N
# points) -> Sign Voxel Filter -> Chunked Marching Cubes -> the volume saved as
# .lvdv (Apps/ParaViewPlugin/Testing/bench_sparse_chain.py), under
# /usr/bin/time -v for the wall time and the peak RSS. Prints the stage lines
# and one Markdown row per N for docs/BENCHMARKS.md.
# Usage: scripts/bench-sparse-chain-pvbatch.sh MESH N [N ...]
# Env: PV_BUILD_DIR (default build-pv), LVDIF_PVSHIM (default /opt/lvdif-pvshim).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 2 ] || { echo "usage: $0 MESH N [N ...]" >&2; exit 2; }
MESH="$1"; shift
[ -f "$MESH" ] || { echo "bench: no mesh $MESH" >&2; exit 1; }
SHIM="${LVDIF_PVSHIM:-/opt/lvdif-pvshim}"
plugin=$(cat "${PV_BUILD_DIR:-$here/build-pv}/lvdif-plugin-path.txt")
[ -f "$plugin" ] || { echo "bench: no plugin $plugin (scripts/build-paraview-plugin.sh)" >&2; exit 1; }
export LVDIF_PV_PYTHONPATH="$SHIM/pvpy/usr/lib/python3/dist-packages"
export PYTHONPATH="$here/Apps/ParaViewPlugin/Testing:$here/Testing/Support:$LVDIF_PV_PYTHONPATH"
export VTK_SMP_BACKEND_IN_USE="${VTK_SMP_BACKEND_IN_USE:-STDThread}"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc --all) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(free -g | awk '/Mem:/ {print $2}') GiB," \
  "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%Y-%m-%dT%H:%MZ)"
echo "mesh: $(basename "$MESH")"
rows=()
for N in "$@"; do
  echo "== N = $N"
  /usr/bin/time -v xvfb-run -a -s "-screen 0 640x480x24 -noreset" pvbatch --force-offscreen-rendering \
    "$here/Apps/ParaViewPlugin/Testing/bench_sparse_chain.py" "$plugin" "$MESH" "$N" "$tmp/out.lvdv" \
    2>"$tmp/time.log" | tee "$tmp/run.log"
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n=split($2,t,":"); s=0; for(i=1;i<=n;i++) s=s*60+t[i]; print s}' "$tmp/time.log")
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2/1024}' "$tmp/time.log")
  grep -q '^BENCH' "$tmp/run.log" || { cat "$tmp/time.log" >&2; echo "bench: the run failed" >&2; exit 1; }
  b=$(grep '^BENCH' "$tmp/run.log")
  val() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$b"; }
  rows+=("| $N | $(val dims) | $(val sdf_s) | $(val svf_s) | $(val mc_s) | $(val write_s) | $wall | **$rss** | $(val sdf_output_mib) / $(val svf_output_mib) | $(val triangles) | $(val file_mib) |")
done
echo
echo "| N | grid | Mesh To SDF (s) | Sign Voxel Filter (s) | Marching Cubes (s) | write .lvdv (s) | process wall (s) | peak RSS (MiB) | Mesh To SDF / Sign Voxel Filter output (MiB) | triangles | file (MiB) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
