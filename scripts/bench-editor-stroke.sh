#!/bin/bash
# The CPU target in the Qt editor: bench_stroke_latency_core's 512^3 stroke
# (100 samples at 50 Hz along a 90-degree arc on a sphere of radius 0.35 N, Add,
# Drill) replayed by lvdif-editor --benchmark-stroke on the same sphere, radius
# 15 and 40, on 2 cores (taskset -c 0,1, OMP_NUM_THREADS=2), under Xvfb: the
# latency from each sample's recorded time to the end of the render of the frame
# that shows it (p50/p95/max), frames drawn included (Mesa llvmpipe under Xvfb:
# software OpenGL, which also takes those 2 cores).
# usage: [EDITOR_ARGS=--full-redraw] scripts/bench-editor-stroke.sh BUILD_DIR [N=512] [RUNS=1]
#   BUILD_DIR: a full build (bin/lvdif-editor) with the Core benchmarks
#   (Testing/Benchmarks/Core/bench_stroke_latency_core). Files and logs in $OUT
#   (default ./out-editor-stroke); stdout: the load and each run's report.
#   EDITOR_ARGS: more lvdif-editor options, e.g. --full-redraw (every frame
#   drawn whole, as before partial redraws) for the comparison, or
#   "--stroke-lod on|off" (default auto: coarse meshes for frames that changed
#   24 or more chunks). Each report says whether its latency counts coarse
#   meshes, and its "refine" line the time from the stroke's end until every
#   chunk it changed shows its full-resolution mesh.
set -u
B=${1:?usage: scripts/bench-editor-stroke.sh BUILD_DIR [N] [RUNS]}
N=${2:-512}
RUNS=${3:-1}
OUT=${OUT:-out-editor-stroke}
mkdir -p "$OUT"
CORE=$B/Testing/Benchmarks/Core/bench_stroke_latency_core
EDITOR=$B/bin/lvdif-editor
for f in "$CORE" "$EDITOR"; do
  [ -x "$f" ] || { echo "missing $f (build lvdif-editor and bench_stroke_latency_core in $B)" >&2; exit 1; }
done
"$CORE" "$N" --write-stroke "$OUT/stroke$N.jsonl" --write-volume "$OUT/sphere$N.lvdv" || exit 1
{ date -u; lscpu | grep "Model name"; } | tee "$OUT/machine.txt"
for r in 15 40; do
  for i in $(seq "$RUNS"); do
    L="$OUT/editor-r$r-run$i${EDITOR_ARGS:+-full}.log"
    echo "## radius $r run $i, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
    OMP_NUM_THREADS=2 taskset -c 0,1 timeout 900 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
      "$EDITOR" --open "$OUT/sphere$N.lvdv" --op add --brush drill --radius "$r" --color "#e65032" \
      --size 640x669 --no-recovery --autosave 0 --benchmark-stroke "$OUT/stroke$N.jsonl" ${EDITOR_ARGS:-} > "$L" 2>&1
    echo "rc=$?, load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$L"
    grep "^benchmark-stroke:" "$L" | grep -v "frames are drawn by" # latency, refine, frames, render, ...
  done
done
