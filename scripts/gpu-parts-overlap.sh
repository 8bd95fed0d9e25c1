#!/bin/bash
# GPU-host A/B of the parts check beside the GPU's distance pass, with every
# Core test executable of the working tree (CUDA tests included) in the same
# lease: builds Core alone with CUDA (sm_90) twice, in parallel, from a tarball
# of the old code (`git archive REV > .gpu/before.tar`) and from the working
# tree; runs the tests one executable at a time; then alternates the builds'
# bench_mesh_to_sdf one-call runs (Device::Auto, dictionary volume, band 8,
# --trace): sub4 (13.3M triangles) at 1024^3 winding (cold, warm, warm) and the
# armadillo at 1024^3 pseudo-normal, two rounds of opposite order.
# No new step starts after BUDGET seconds (default 420). Logs in $OUT.
# usage: OUT=dir scripts/gpu-parts-overlap.sh [BEFORE.tar] [ARMADILLO.off] [BUDGET]
set -u
BEFORE=${1:-.gpu/before.tar}
A=${2:-.gpu/meshes/armadillo.off}
BUDGET=${3:-420}
OUT=${OUT:-out-gpu-parts}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] && [ -f "$BEFORE" ] || { echo "need $A and $BEFORE"; exit 1; }
gpu_begin
mkdir -p /tmp/before && tar -xf "$BEFORE" -C /tmp/before
gpu_build_ab bench_mesh_to_sdf "bench_mesh_to_sdf $(gpu_core_test_targets)"
gpu_core_tests b-after 200
: > "$L"
for order in "before after" "after before"; do
  for b in $order; do
    RUN_LABEL=$b run 90 "b-$b/Testing/Benchmarks/Core/bench_mesh_to_sdf" "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace
    RUN_LABEL=$b run 60 "b-$b/Testing/Benchmarks/Core/bench_mesh_to_sdf" "$A" 1024 pseudonormal auto bvh volume 8 2 cold,warm --trace
  done
done
grep -E "^## |^\| (cold|warm) |connected parts|rc=[1-9]" "$L" | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
