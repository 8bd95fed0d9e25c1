#!/usr/bin/env bash
# MPI scaling of the plugin pipeline (mesh -> SDF -> marching cubes -> write)
# under pvbatch with 1, 2 and 4 ranks; prints a Markdown table for
# docs/BENCHMARKS.md ("MPI scaling"). Builds the plugin first.
# Usage: scripts/bench-paraview-mpi.sh [N (grid points per axis, default 192)] [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
N="${1:-192}"
B="${2:-$here/build-pv}"
SHIM="${LVDIF_PVSHIM:-/opt/lvdif-pvshim}"
plugin=$("$here/scripts/build-paraview-plugin.sh" "$B" "$SHIM" | tail -n1)
export LVDIF_PV_PYTHONPATH="$SHIM/pvpy/usr/lib/python3/dist-packages"
export PYTHONPATH="$here/Apps/ParaViewPlugin/Testing:$here/Testing/Support:$LVDIF_PV_PYTHONPATH"
export VTK_SMP_BACKEND_IN_USE="${VTK_SMP_BACKEND_IN_USE:-STDThread}" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
script="$here/Apps/ParaViewPlugin/Testing/mpi_pipeline.py"
echo "machine: $(nproc --all) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), VTK_SMP_BACKEND_IN_USE=$VTK_SMP_BACKEND_IN_USE, OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}, load: $(cut -d" " -f1-3 /proc/loadavg)"
echo
echo "| ranks | SDF stage | surface | grid | pipeline (s) | write (s) | triangles |"
echo "|---|---|---|---|---|---|---|"
for np in 1 2 4; do
  line=$(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" mpirun --allow-run-as-root --oversubscribe -np "$np" \
    pvbatch --force-offscreen-rendering "$script" "$plugin" "$tmp" --bench --n "$N" 2>&1 | grep '^BENCH' || true)
  [ -n "$line" ] || { echo "bench-paraview-mpi: run with $np ranks failed" >&2; exit 1; }
  eval "$(echo "$line" | sed 's/^BENCH //; s/ /;/g')"
  echo "| $ranks | $sdf | $surface | ${N}^3 | $pipeline_s | $write_s | $triangles |"
done
rm -rf "$tmp"
