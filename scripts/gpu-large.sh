#!/bin/bash
# GPU-host check of the large-mesh targets: reading a generated 10M-triangle
# binary PLY (and OFF) against one fread of the same file, then the armadillo
# subdivided four times in memory (sub4, 13.3M triangles) at 1024^3,
# WindingNumber, Device::Auto, into the dictionary volume, band 8 (cold, warm,
# with --trace for the host phases). Builds Core-only with CUDA (sm_90); no new
# step starts after BUDGET seconds (default 240). Logs in $OUT.
# usage: OUT=dir scripts/gpu-large.sh [ARMADILLO.off] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-240}
OUT=${OUT:-out-gpu-large}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
gpu_begin
gpu_build b-large bench_mesh_to_sdf bench_mesh_read
B=b-large/Testing/Benchmarks/Core
: > "$L"
# the target: a 10M-triangle binary PLY read in <= 1 s (files in /tmp, removed after)
run 90 "$B/bench_mesh_read" 10000000 /tmp ply,off
# the target: a 10M-triangle mesh at 1024^3 in <= 2 s (warm, the file's reading excluded)
run 150 "$B/bench_mesh_to_sdf" "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace
{
  grep -E "^## |^\| (format|[a-z ]*ply|off|stl)|^\| (cold|warm) |rc=[1-9]" "$L"
  grep -E "\[mesh to SDF\] (prepareMesh|mesh BVH|winding|upload and session)" "$L" | head -20
} | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
