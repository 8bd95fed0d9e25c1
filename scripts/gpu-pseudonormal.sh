#!/bin/bash
# GPU-host session for the far blocks of the Normal and PseudoNormal signs
# (docs/MESH_TO_SDF.md "Far blocks": blocks, halves, cells and voxels, with
# candidate lists handed down): builds Core-only with CUDA (sm_90), runs the
# CUDA tests and the CPU far-block tests (MeshToSdfCuda.*: the GPU against its
# per-voxel path and the CPU bit for bit), then bench_mesh_to_sdf at 1024^3
# into the dictionary volume (band 8), warm one-call runs: winding,
# pseudo-normal and normal (twice each, same process), prepared runs and one
# per-voxel pseudo-normal run for reference, on the bunny and the armadillo,
# one process per mesh (--trace: the distance pass split into the far-block
# kernels and the per-voxel kernel); last a CPU run at 512^3 on all cores (same-run ratios
# to winding). Stops starting runs after BUDGET seconds (default 300).
# usage: OUT=dir scripts/gpu-pseudonormal.sh [MESHDIR=.gpu/meshes] [BUDGET]
#   MESHDIR holds armadillo.off and lvdif-bunny-30k.ply (run from the repository root)
set -u
D=${1:-.gpu/meshes}
BUDGET=${2:-300}
A=$D/armadillo.off
BUNNY=$D/lvdif-bunny-30k.ply
OUT=${OUT:-out-gpu-pseudonormal}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_begin
gpu_build b-pn LVDIFMeshToSdfTests bench_mesh_to_sdf

# tests: the CUDA ones and the CPU far blocks, then the far-block lines
timeout 150 b-pn/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter='MeshToSdfCuda.*:MeshToSdfFarBlocks.*' \
  > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |^\[  FAILED  \]" "$OUT/tests.log" | sort -u | tee -a "$OUT/summary.txt"
grep -E "^\[ far blocks cuda \]" "$OUT/tests.log" | grep -E "sphere|box|armadillo|slivers" | head -8 | tee -a "$OUT/summary.txt"

M=b-pn/Testing/Benchmarks/Core/bench_mesh_to_sdf
# bench_mesh_to_sdf MESH RES SIGN DEVICE ACCEL OUTPUT BAND PADDING RUNS (RUN@SIGN[@pervoxel])
GPU_RUNS=cold,warm@winding,warm@pseudonormal,warm@normal,warm@winding,warm@pseudonormal,warm@normal
GPU_RUNS=$GPU_RUNS,prepared@winding,prepared@pseudonormal,prepared@normal,warm@pseudonormal@pervoxel
for m in "$BUNNY" "$A"; do
  run 60 $M "$m" 1024 winding auto bvh volume 8 2 "$GPU_RUNS" --trace
done
# the CPU on all cores, 512^3: same-run ratios to winding
run 60 $M "$A" 512 winding cpu bvh volume 8 2 \
  warm@winding,prepared@winding,prepared@pseudonormal,prepared@normal,prepared@winding
grep -E "^mesh:|^\| (cold|warm|prepared)|^## SKIPPED|^rc=[1-9]" "$L" | cut -c1-150 >> "$OUT/summary.txt"
# --trace at 1024^3: the GPU distance pass of each far-block call (warm pseudo-normal, normal,
# pseudo-normal, normal, then prepared pseudo-normal, normal: the runs' order) split into
# farBlockKernel, farCellKernel and the per-voxel kernel, under each process's command
grep -E "^## .* 1024 |distance pass on the GPU|node cones of the mesh BVH" "$L" | cut -c1-150 | tee "$OUT/far-split.txt" >> "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
# the short table on stdout: run, device, end-to-end ms, far-block voxels
cat "$OUT/far-split.txt"
awk -F'|' '/^mesh:/ { print substr($0, 1, 110) } /^\| (cold|warm|prepared)/ { printf "%-34s %-5s %10s ms  far %s\n", $2, $3, $9, $15 }' "$L"
