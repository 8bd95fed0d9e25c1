#!/bin/bash
# GPU-host run for the Normal sign of solids by the winding path and the sharp
# features' regions (MeshToSdfOptions::solidsByWinding, docs/MESH_TO_SDF.md
# "Normal signs of solids"): builds Core alone with CUDA (sm_90), runs every
# Core test executable one after the other (CUDA tests included), then
# bench_mesh_to_sdf one-call runs into the dictionary volume (band 8, --trace):
# on CUDA at 1024^3 (the regions' bricks on the host, their voxels on the GPU,
# both beside the GPU's winding pass)
# the armadillo with winding, normal (the route) and normal by its own path
# (@normalspath), alternating, then sub2 (832k triangles); then on the host's
# CPU threads the armadillo at 512^3 and 1024^3. No new step after BUDGET s.
# usage: OUT=dir scripts/gpu-normal-solids.sh [ARMADILLO.off] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-480}
OUT=${OUT:-out-gpu-normal-solids}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_tests_then_bench "$A"
R=cold,warm@winding,warm@normal,warm@normal@normalspath,warm@normal@normalspath,warm@normal,warm@winding
R=$R,warm@winding,warm@normal,warm@normal@normalspath
run 90 $M "$A" 1024 normal auto bvh volume 8 2 "$R" --trace
run 60 $M "sub2:$A" 1024 normal auto bvh volume 8 2 cold,warm@winding,warm@normal,warm@normal@normalspath,warm@normal,warm@winding --trace
run 100 $M "$A" 512 normal cpu bvh volume 8 2 cold,warm@winding,warm@normal,warm@normal@normalspath,warm@winding,warm@normal --trace
run 90 $M "$A" 1024 normal cpu bvh volume 8 2 cold,warm@winding,warm@normal --trace
grep -E "^## |^mesh:|^machine:|^\| (cold|warm|prepared)|sharp features|rc=[1-9]" "$L" | cut -c1-170 | tee -a "$OUT/summary.txt"
# one warm normal call's whole trace on CUDA (where its time goes)
run 30 $M "$A" 1024 normal auto bvh volume 8 2 cold,warm@normal --trace
awk '/^## .*cold,warm@normal --trace/{on=1} on' "$L" | grep -E "^\[mesh to SDF\]|^\| warm" | tail -40 | tee -a "$OUT/summary.txt"
# sub2's warm normal call: where its build goes (the parts, the solid check's steps)
run 40 $M "sub2:$A" 1024 normal auto bvh volume 8 2 cold,warm@winding,warm@normal --trace
awk '/^## .*sub2.*cold,warm@winding,warm@normal --trace/{on=1} on' "$L" | grep -E "^\[mesh to SDF\]|^\| warm" | tail -45 | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
