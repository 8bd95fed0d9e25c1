#!/bin/bash
# GPU-host A/B of the one-call CUDA path's host build, in one lease: builds
# Core alone with CUDA (sm_90) twice, from a source tarball of the old code
# (BEFORE, made here with `git archive REV > .gpu/before.tar`) and from the
# working tree, in parallel (the old tree gets the working tree's
# bench_mesh_to_sdf_build.cpp, so both time the same host phases); runs the
# working tree's MeshToSdf CUDA, build, far-block/band and orientation tests
# and the Memory tests; then alternates the two builds' bench_mesh_to_sdf on
# the 13.3M-triangle sub4 of the armadillo, the 832k-triangle sub2 and the
# paper's bunny at 1024^3 (WindingNumber, Device::Auto, dictionary volume,
# band 8; cold then warm calls, --trace), sub4 in a second round in the other
# order, times sub4's host build phases (bench_mesh_to_sdf_build: the one-call
# route's prepare with the tree beside the edge pass, the tree alone, the
# serial head of one split) with both, and checks sub2 CUDA = CPU bit for bit
# at 128^3 with the new build. No new step starts after BUDGET seconds
# (default 540). Logs in $OUT.
# usage: OUT=dir scripts/gpu-meshbuild-ab.sh [BEFORE.tar] [ARMADILLO.off] [BUNNY.ply] [BUDGET]
set -u
BEFORE=${1:-.gpu/before.tar}
A=${2:-.gpu/meshes/armadillo.off}
BUNNY=${3:-.gpu/meshes/lvdif-bunny-30k.ply}
BUDGET=${4:-540}
OUT=${OUT:-out-gpu-meshbuild-ab}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
[ -f "$BEFORE" ] || { echo "no tarball of the old code at $BEFORE"; exit 1; }
gpu_begin
mkdir -p /tmp/before && tar -xf "$BEFORE" -C /tmp/before
cp Testing/Benchmarks/Core/bench_mesh_to_sdf_build.cpp /tmp/before/Testing/Benchmarks/Core/
gpu_build_ab "bench_mesh_to_sdf bench_mesh_to_sdf_build" "bench_mesh_to_sdf bench_mesh_to_sdf_build LVDIFMeshToSdfTests LVDIFCommonTests"

# the CUDA tests (the GPU against the CPU bit for bit), the build's and the band's
timeout 150 b-after/Core/MeshToSdf/LVDIFMeshToSdfTests \
  --gtest_filter='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*:MeshToSdfBuild.*:MeshToSdf.PreparedMesh*:MeshToSdfFarBlocks.*:MeshToSdfWindingFlip.OrientationIsIndependentOfThreads' \
  > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
timeout 60 b-after/Core/Common/LVDIFCommonTests --gtest_filter='Memory.*' >> "$OUT/tests.log" 2>&1
echo "Memory tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |Failure" "$OUT/tests.log" | head -20 | tee -a "$OUT/summary.txt"

: > "$L"
B=Testing/Benchmarks/Core
# sub4 first (the open target), then sub2 and the bunny, then sub4 again in the other order
for v in before after; do
  RUN_LABEL="$v r1" run 90 b-$v/$B/bench_mesh_to_sdf "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace
done
for v in before after; do
  RUN_LABEL="$v r1" run 60 b-$v/$B/bench_mesh_to_sdf "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm --trace
  RUN_LABEL="$v r1" run 40 b-$v/$B/bench_mesh_to_sdf "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm --trace
done
for v in after before; do
  RUN_LABEL="$v r2" run 90 b-$v/$B/bench_mesh_to_sdf "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace
done
for v in before after; do
  RUN_LABEL="$v" run 90 env LVDIF_BUILD_TRACE=1 b-$v/$B/bench_mesh_to_sdf_build "sub4:$A" 1 beside,bvh,serialhead
done
RUN_LABEL=after run 60 b-after/$B/bench_mesh_to_sdf "sub2:$A" 128 winding auto bvh float 0 2 warm --check-cpu

{
  echo "## rows (ms): run | device | read | build | distance | sign | write | end-to-end"
  grep -E "^## |^\| (cold|warm) |^cpu check:|rc=[1-9]" "$L" | grep -v "^## .*bench_mesh_to_sdf_build" |
    awk -F'|' '/^\| (cold|warm) / { printf "|%s|%s|%s|%s|%s|%s|%s|%s|\n", $2, $3, $4, $5, $6, $7, $8, $9; next } { print }'
  echo "## host phases (--trace), in run order"
  grep -E "^## |\[mesh to SDF\] (prepareMesh|prepare:|mesh BVH|winding structures|upload and session)" "$L" | head -200
  echo "## host build phases of sub4 (bench_mesh_to_sdf_build, ms)"
  grep -E "^## .*bench_mesh_to_sdf_build|^\| (prepareMesh|mesh Bvh|one split)" "$L"
} | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
