#!/bin/bash
# GPU-host check of every target of issue #19 in one run, on the working tree:
# builds Core alone with CUDA (sm_90), runs every Core test executable (CUDA
# ones included), then measures
#   - reading a generated 10M-triangle binary PLY (<= 1 s),
#   - the armadillo subdivided twice (sub2, 832k triangles) and four times
#     (sub4, 13.3M) at 1024^3, warm, into the dictionary volume (<= 400 ms, <= 2 s),
#   - the paper's bunny at 1024^3, warm, one call (<= 200 ms),
#   - the armadillo's normal and pseudo-normal calls against its winding calls
#     at 1024^3 (<= 1.5x), under the default OpenMP waits and passive ones.
# The damaged meshes (<= 2x the clean mesh) have their own run:
# scripts/gpu-damaged.sh.
# The banded comparison with OpenVDB runs on the VM (no OpenVDB on the GPU
# host): bench_mesh_to_sdf_band_vdb, docs/BENCHMARKS.md.
# No new step starts after BUDGET seconds (default 480). Key lines on stdout.
# usage: OUT=dir scripts/gpu-targets19.sh [ARMADILLO.off] [BUNNY.ply] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUNNY=${2:-.gpu/meshes/lvdif-bunny-30k.ply}
BUDGET=${3:-480}
OUT=${OUT:-out-gpu-targets19}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
gpu_begin
gpu_build b $(gpu_core_test_targets) bench_mesh_to_sdf bench_mesh_read
gpu_core_tests b 200
B=b/Testing/Benchmarks/Core
: > "$L"
# bench LIMIT LABEL ARGS...: one bench_mesh_to_sdf process as `run` step LABEL
bench() { local lim=$1 label=$2; shift 2; RUN_LABEL=$label run "$lim" "$B/bench_mesh_to_sdf" "$@"; }
RUN_LABEL="ply read" run 90 "$B/bench_mesh_read" 10000000 /tmp ply
[ -f "$BUNNY" ] && bench 40 "bunny 1024" "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm
bench 60 "sub2 1024" "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm
for s in winding pseudonormal normal; do bench 40 "armadillo 1024 $s" "$A" 1024 "$s" auto bvh volume 8 2 cold,warm,warm,warm; done
for s in pseudonormal normal; do OMP_WAIT_POLICY=passive bench 40 "armadillo 1024 $s passive" "$A" 1024 "$s" auto bvh volume 8 2 cold,warm,warm,warm; done
bench 150 "sub4 1024" "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm
{
  grep -E "^## |^\| [a-z ]*ply|^\| warm |rc=[1-9]" "$L"
} | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
