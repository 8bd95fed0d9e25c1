#!/bin/bash
# GPU-host session for robust winding signs (no VTK there): builds Core-only
# with CUDA (sm_90), runs the MeshToSdf tests (CUDA equality ones included),
# then the mesh-to-SDF benchmark on clean and damaged meshes (damaged variants
# are made in memory, seeded: Testing/Benchmarks/Core/SignQualityMeshes.h).
# Every step has a time limit and the whole script stops starting new runs
# after BUDGET seconds (default 420), so it ends in under 8 minutes.
# usage: OUT=dir scripts/gpu-signs.sh ARMADILLO.off BUNNY.(ply|off) [BUDGET]
#   e.g. scripts/gpu-signs.sh Data/extracted/armadillo.off /path/lvdif-bunny-30k.ply
# (run from the repository root; scripts/extract-meshes.sh makes the .off files)
set -u
A=${1:?armadillo mesh}
BUNNY=${2:?bunny mesh}
BUDGET=${3:-420}
OUT=${OUT:-out-gpu-signs}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_begin
gpu_build b-signs LVDIFMeshToSdfTests LVDIFFormatsTests bench_mesh_to_sdf bench_winding_flip bench_mesh_read

# tests: every MeshToSdf test, the CUDA = CPU equality ones included
timeout 180 b-signs/Core/MeshToSdf/LVDIFMeshToSdfTests > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) " "$OUT/tests.log" | tee -a "$OUT/summary.txt"
timeout 60 b-signs/Core/Formats/LVDIFFormatsTests > "$OUT/tests_formats.log" 2>&1
echo "Formats tests rc=$?" | tee -a "$OUT/summary.txt"

B=b-signs/Testing/Benchmarks/Core
# bench_mesh_to_sdf SPEC RES SIGN DEVICE ACCEL OUTPUT BAND PADDING RUNS
M="$B/bench_mesh_to_sdf"
# the paper's bunny at 1024^3, one call (cold then warm), and prepared
run 40 $M "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,prepared
# pseudo-normal / normal vs winding at 1024^3 (same mesh, same grid)
run 40 $M "$A" 1024 winding auto bvh volume 8 2 cold,warm
run 40 $M "$A" 1024 pseudonormal auto bvh volume 8 2 cold,warm
run 40 $M "$A" 1024 normal auto bvh volume 8 2 warm
# clean vs damaged armadillo at 512^3 under Device::Auto (meshes with
# reversed or duplicated faces stay on the CPU, all cores, until the CUDA
# construction exists; holes and fins go to the GPU)
run 30 $M "$A" 512 winding auto bvh volume 8 2 cold,warm
for d in patch10 duprev20 holes40 fins200 pair; do
  run 45 $M "$d:$A" 512 winding auto bvh volume 8 2 warm
done
# 1024^3: clean above; holes (GPU under Auto)
run 40 $M "holes40:$A" 1024 winding auto bvh volume 8 2 warm
# (patch10 at 1024^3 stays on the CPU under Auto: over 60 s on 16 threads in the first run)
# 832k triangles (armadillo, 2 levels of midpoint subdivision) at 1024^3
run 60 $M "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,prepared
# reading a generated 10M-triangle mesh: binary PLY and OFF (files in /tmp, removed after)
run 90 "$B/bench_mesh_read" 10000000 /tmp ply,off
# the text readers on threads: ASCII PLY and OBJ (2M triangles; 1 thread, then all)
run 60 env OMP_NUM_THREADS=1 "$B/bench_mesh_read" 2000000 /tmp asciiply,obj
run 60 "$B/bench_mesh_read" 2000000 /tmp asciiply,obj
# host builds on the 832k-triangle mesh: nearest index (CPU) with 1 thread and all threads, phase times
run 60 env OMP_NUM_THREADS=1 $M "sub2:$A" 64 unsigned cpu bvh float 4 2 cold --trace
run 60 $M "sub2:$A" 64 unsigned cpu bvh float 4 2 cold --trace
run 60 $M "patch10:sub2:$A" 64 winding cpu bvh float 4 2 cold --trace
# CPU ratios on all cores: damaged / clean WindingNumber time at 256^3, with a
# brute-force check of 200 far voxels each
run 120 "$B/bench_winding_flip" --res 256 --samples 200 "$A" "patch10:$A" "duprev20:$A" "holes40:$A" "fins200:$A" \
  "pair:$A" "patch30:$A" "flip10:$A"
# 13.3M triangles (armadillo, 4 levels of subdivision; made in memory first) at 1024^3
run 120 $M "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm
# explicit CUDA on damaged meshes: the GPU's cone construction (slow there)
run 30 $M "patch10:$A" 512 winding cuda bvh volume 8 2 warm
grep -E "^mesh:|^\| (cold|warm|prepared|ply|off|asciiply|obj) |^\[mesh to SDF\]|^## SKIPPED|^rc=1[0-9][0-9]" "$L" >> "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
