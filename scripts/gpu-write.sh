#!/bin/bash
# GPU-host check of the CUDA path into the dictionary volume: the chunk keys
# back in pieces through pinned staging (the store under the copies and the
# next group's kernels), the distance kernel's far runs, the sign kernels'
# ray split over the warp. Builds Core-only with CUDA (sm_90), runs the CUDA
# tests of MeshToSdf (CUDA = CPU bit for bit; keys in many pieces, pinned and
# pageable) and the ray-walk test, checks the bunny and sub2 CUDA = CPU bit for
# bit at 128^3, then times the paper's bunny and the 832k-triangle armadillo
# (sub2, made in memory) at 1024^3, WindingNumber, Device::Auto, into the
# volume, band 8, warm, with --trace (the write's parts), and the same warm
# call with the keys through pageable memory (@pageable) in the same process,
# and warm calls without --trace (its phase timers wait for the GPU).
# Every step has a time limit; no new step starts after BUDGET seconds
# (default 270), so the script ends within about 5 minutes. Logs in $OUT
# (machine, build, tests, bench, summary).
# usage: OUT=dir scripts/gpu-write.sh [ARMADILLO.off] [BUNNY.ply] [BUDGET]
#   defaults: .gpu/meshes/armadillo.off and .gpu/meshes/lvdif-bunny-30k.ply
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUNNY=${2:-.gpu/meshes/lvdif-bunny-30k.ply}
BUDGET=${3:-270}
OUT=${OUT:-out-gpu-write}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
[ -f "$BUNNY" ] || { echo "no mesh at $BUNNY"; exit 1; }
gpu_begin
gpu_build b-write LVDIFMeshToSdfTests bench_mesh_to_sdf

# CUDA = CPU bit for bit (closed, intersecting, damaged meshes, prepared reuse,
# keys in pieces pinned and pageable); the split ray against Bvh::rayHits
timeout 150 b-write/Core/MeshToSdf/LVDIFMeshToSdfTests \
  --gtest_filter='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*:MeshToSdfRayWalk.*' > "$OUT/tests.log" 2>&1
echo "MeshToSdf CUDA tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |Failure|keys in pieces|ray walk" "$OUT/tests.log" | head -30 | tee -a "$OUT/summary.txt"

M=b-write/Testing/Benchmarks/Core/bench_mesh_to_sdf
: > "$L"
# CUDA = CPU bit for bit on the two benchmark meshes (128^3 float grid, no band)
run 40 $M "$BUNNY" 128 winding auto bvh float 0 2 warm --check-cpu
run 60 $M "sub2:$A" 128 winding auto bvh float 0 2 warm --check-cpu
# the targets: the bunny <= 200 ms warm, sub2 (832k) <= 400 ms warm including the build
run 60 $M "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm,warm@pageable,warm,prepared --trace
run 60 $M "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm@pageable,prepared --trace

# the same without --trace
run 40 $M "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm

{
  echo "## rows (ms): run | device | read | build | distance | sign | write | end-to-end | inside voxels | expanded chunks"
  grep -E "^## |^\| (cold|warm|prepared)|^cpu check:|^device memory|rc=[1-9]" "$L" |
    awk -F'|' '/^\| (cold|warm|prepared)/ { printf "|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", $2, $3, $4, $5, $6, $7, $8, $9, $12, $13; next } { print }'
  echo "## the write's parts and the sign's (--trace), in run order"
  grep -E "^## |\[mesh to SDF\] (write|upload and session|winding structures built|winding sign on the GPU, dictionary)|pinned host memory" "$L" | head -200
} | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
