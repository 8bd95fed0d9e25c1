#!/bin/bash
# GPU-host check of the host build of mesh to SDF (mesh preparation, the
# mesh BVH shared with a closed mesh's winding closure, the upload): builds
# Core-only with CUDA (sm_90), runs the CUDA tests of MeshToSdf (CUDA = CPU
# bit for bit), then times the paper's bunny and the 832k-triangle armadillo
# (sub2, two midpoint subdivisions made in memory) at 1024^3, WindingNumber,
# Device::Auto, into the dictionary volume, band 8 (cold, warm, warm,
# prepared; --trace gives the host phases), and checks sub2 CUDA = CPU bit for
# bit at 128^3. Every step has a time limit; no new step starts after BUDGET
# seconds (default 300), so the script ends in under 6 minutes (about 2 on an
# H100 host with 16 cores). Logs in $OUT (machine, build, tests, bench,
# summary).
# usage: OUT=dir scripts/gpu-meshbuild.sh [ARMADILLO.off] [BUNNY.ply] [BUDGET]
#   defaults: .gpu/meshes/armadillo.off and .gpu/meshes/lvdif-bunny-30k.ply
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUNNY=${2:-.gpu/meshes/lvdif-bunny-30k.ply}
BUDGET=${3:-300}
OUT=${OUT:-out-gpu-meshbuild}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
gpu_begin
gpu_build b-meshbuild LVDIFMeshToSdfTests bench_mesh_to_sdf bench_mesh_to_sdf_build

# the CUDA tests (CUDA = CPU bit for bit: closed, intersecting, damaged meshes, prepared reuse)
# (and the host build's: prepareMesh with and without the pseudo-normals added later = a
# serial reference, bit for bit; a prepared mesh used for Unsigned, then PseudoNormal)
timeout 150 b-meshbuild/Core/MeshToSdf/LVDIFMeshToSdfTests \
  --gtest_filter='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*:MeshToSdfBuild.*:MeshToSdf.PreparedMesh*' \
  > "$OUT/tests.log" 2>&1
echo "MeshToSdf CUDA tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |Failure" "$OUT/tests.log" | head -20 | tee -a "$OUT/summary.txt"

B=b-meshbuild/Testing/Benchmarks/Core
: > "$L"
M="$B/bench_mesh_to_sdf"
# the targets: the bunny <= 200 ms warm, sub2 (832k) <= 400 ms warm including the build
[ -f "$BUNNY" ] && run 40 $M "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm,prepared --trace
run 60 $M "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm,prepared --trace
# PseudoNormal prepares the pseudo-normals at once (the other signs skip them): the same path as before
run 60 $M "sub2:$A" 1024 pseudonormal auto bvh volume 8 2 warm,warm
# CUDA = CPU bit for bit on sub2 (128^3 float grid, no band; the CPU on all cores)
run 60 $M "sub2:$A" 128 winding auto bvh float 0 2 warm --check-cpu
# the host build phases alone (all cores), with hashes of what they built, and how
# the first touch of fresh memory scales (1 thread, all, huge pages)
run 60 "$B/bench_mesh_to_sdf_build" "sub2:$A" 3 prepare,bvh,winding,gpuhost,nearest,touch

{
  echo "## warm/prepared rows (ms): run | device | read | build | distance | sign | write | end-to-end"
  grep -E "^## |^\| (cold|warm|prepared) |^cpu check:|^prepareMeshToSdf|^\| (prepareMesh|mesh Bvh|WindingSigner|GPU path|NearestIndex|first touch|  then addPseudoNormals|  the same with) |rc=[1-9]" "$L" |
    awk -F'|' '/^\| (cold|warm|prepared) / { printf "|%s|%s|%s|%s|%s|%s|%s|%s|\n", $2, $3, $4, $5, $6, $7, $8, $9; next } { print }'
  echo "## host phases (--trace), in run order"
  grep -E "^## |\[mesh to SDF\] (prepareMesh|prepare:|pseudo-normals|mesh BVH|winding|upload and session|write)" "$L" | head -200
} | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
