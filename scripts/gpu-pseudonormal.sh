#!/bin/bash
# GPU-host session for the far blocks of the Normal and PseudoNormal signs
# (docs/MESH_TO_SDF.md "Far blocks"): builds Core-only with CUDA (sm_90), runs
# the MeshToSdf tests (the CUDA far-block test compares the GPU with its
# per-voxel path and with the CPU), then bench_mesh_to_sdf at 1024^3 into the
# dictionary volume (band 8), warm one-call runs: winding, pseudo-normal and
# normal with far blocks, and both normal modes per voxel (the old path), on
# the bunny and the armadillo, one process per mesh; last a CPU run at 512^3
# on all cores. Stops starting runs after BUDGET seconds (default 480).
# usage: OUT=dir scripts/gpu-pseudonormal.sh [MESHDIR=.gpu/meshes] [BUDGET]
#   MESHDIR holds armadillo.off and lvdif-bunny-30k.ply (run from the repository root)
set -u
D=${1:-.gpu/meshes}
BUDGET=${2:-480}
A=$D/armadillo.off
BUNNY=$D/lvdif-bunny-30k.ply
OUT=${OUT:-out-gpu-pseudonormal}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_begin
gpu_build b-pn LVDIFMeshToSdfTests bench_mesh_to_sdf

# tests: every MeshToSdf test (CUDA ones included), then the far-block lines
timeout 240 b-pn/Core/MeshToSdf/LVDIFMeshToSdfTests > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |^\[  FAILED  \]" "$OUT/tests.log" | sort -u | tee -a "$OUT/summary.txt"
grep -E "^\[ far blocks cuda \]" "$OUT/tests.log" | grep -E "sphere|armadillo|slivers" | head -8 | tee -a "$OUT/summary.txt"

M=b-pn/Testing/Benchmarks/Core/bench_mesh_to_sdf
# bench_mesh_to_sdf MESH RES SIGN DEVICE ACCEL OUTPUT BAND PADDING RUNS (RUN@SIGN[@pervoxel])
GPU_RUNS=cold,warm@winding,warm@pseudonormal,warm@normal,warm@winding,warm@pseudonormal,warm@normal
GPU_RUNS=$GPU_RUNS,warm@pseudonormal@pervoxel,warm@normal@pervoxel,prepared@winding,prepared@pseudonormal,prepared@normal
for m in "$BUNNY" "$A"; do
  run 90 $M "$m" 1024 winding auto bvh volume 8 2 "$GPU_RUNS"
done
# the CPU on all cores, 512^3: same-run ratios to winding, with and without far blocks
run 120 $M "$A" 512 winding cpu bvh volume 8 2 \
  warm@winding,prepared@winding,prepared@pseudonormal,prepared@normal,prepared@pseudonormal@pervoxel
grep -E "^mesh:|^\| (cold|warm|prepared)|^## SKIPPED|^rc=[1-9]" "$L" | cut -c1-150 >> "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
# the short table on stdout: run, device, end-to-end ms, far-block voxels
awk -F'|' '/^mesh:/ { print substr($0, 1, 110) } /^\| (cold|warm|prepared)/ { printf "%-34s %-5s %10s ms  far %s\n", $2, $3, $9, $15 }' "$L"
