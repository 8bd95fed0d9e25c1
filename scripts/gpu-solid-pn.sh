#!/bin/bash
# GPU-host run for the PseudoNormal sign of solids by the winding path
# (MeshToSdfOptions::solidsByWinding, docs/MESH_TO_SDF.md "Pseudo-normal signs
# of solids"): builds Core alone with CUDA (sm_90), runs every Core test
# executable one after the other (CUDA tests included: MeshToSdfSolid.* checks
# the solid's field against the pseudo-normal path on the GPU too), then
# bench_mesh_to_sdf one-call runs (Device::Auto, dictionary volume, band 8,
# --trace) at 1024^3: the armadillo with winding, pseudo-normal (solid path),
# pseudo-normal by its own path (@normalspath) and normal, twice in
# alternating order, and prepared runs; then sub2 (832k triangles, the solid
# check's cost on many triangles) and patch10 (a damaged mesh: the check fails
# at once) with pseudo-normal and winding. No new step after BUDGET seconds.
# usage: OUT=dir scripts/gpu-solid-pn.sh [ARMADILLO.off] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-420}
OUT=${OUT:-out-gpu-solid-pn}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_tests_then_bench "$A"
R=cold,warm@winding,warm@pseudonormal,warm@pseudonormal@normalspath,warm@normal
R=$R,warm@normal,warm@pseudonormal@normalspath,warm@pseudonormal,warm@winding
R=$R,prepared@winding,prepared@pseudonormal,prepared@pseudonormal@normalspath,prepared@winding,prepared@pseudonormal
run 90 $M "$A" 1024 pseudonormal auto bvh volume 8 2 "$R" --trace
run 90 $M "sub2:$A" 1024 pseudonormal auto bvh volume 8 2 cold,warm,warm@winding,warm,warm@winding --trace
run 60 $M "patch10:$A" 1024 pseudonormal auto bvh volume 8 2 cold,warm,warm@winding --trace
grep -E "^## |^mesh:|^\| (cold|warm|prepared)|solid check|rc=[1-9]" "$L" | cut -c1-160 | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
