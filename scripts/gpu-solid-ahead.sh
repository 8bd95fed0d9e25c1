#!/bin/bash
# GPU-host A/B of session 25's Normal and PseudoNormal calls on CUDA: the solid
# check beside the GPU's pass (SolidCheckBesideGpu) and the sharp-feature search
# on the threads. Builds Core alone with CUDA (sm_90) twice, in parallel: the
# old code from BEFORE (`git archive REV > .gpu/before.tar`) and the working
# tree; runs the working tree's MeshToSdf and Volume tests on the GPU; then
# alternates the two builds' bench_mesh_to_sdf one-call runs (1024^3, Device
# Auto, dictionary volume, band 8, --trace) on sub2 (832k triangles) and the
# armadillo: winding, normal, pseudo-normal, in two rounds of opposite order.
# No new step after BUDGET s. The summary is printed at the end.
# usage: OUT=dir scripts/gpu-solid-ahead.sh [BEFORE.tar] [ARMADILLO.off] [BUDGET]
set -u
BEFORE=${1:-.gpu/before.tar}
A=${2:-.gpu/meshes/armadillo.off}
BUDGET=${3:-480}
OUT=${OUT:-out-gpu-solid-ahead}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$BEFORE" ] && [ -f "$A" ] || { echo "need $BEFORE and $A"; exit 1; }
gpu_begin
rm -rf /tmp/before && mkdir -p /tmp/before && tar -xf "$BEFORE" -C /tmp/before
gpu_build_ab bench_mesh_to_sdf "bench_mesh_to_sdf LVDIFMeshToSdfTests LVDIFVolumeTests"
GPU_TESTS_AT_ONCE=1 gpu_core_tests b-after 300 MeshToSdf Volume
: > "$L"
R=cold,warm@winding,warm@normal,warm@pseudonormal,warm@normal,warm@winding,warm@pseudonormal
for round in ${ROUNDS:-1 2}; do
  for mesh in "sub2:$A" "$A"; do
    order="before after"
    [ "$round" = 2 ] && order="after before"
    for b in $order; do
      RUN_LABEL=$b run 60 "b-$b/Testing/Benchmarks/Core/bench_mesh_to_sdf" "$mesh" 1024 normal auto bvh volume 8 2 "$R" --trace
    done
  done
done
grep -E "^## |^\| (run|cold|warm)|rc=[1-9]" "$L" | cut -c1-150 | tee -a "$OUT/summary.txt"
# the timeline of the working tree's last warm normal call on sub2 (phases by
# when they ended, ms from its first line; durations)
b-after/Testing/Benchmarks/Core/bench_mesh_to_sdf "sub2:$A" 1024 normal auto bvh volume 8 2 cold,warm@winding,warm@normal --trace > "$OUT/timeline.log" 2>&1
n=$(grep -n "solid check beside the GPU's pass: started" "$OUT/timeline.log" | tail -1 | cut -d: -f1)
tail -n +$((n - 12)) "$OUT/timeline.log" | grep "^\[mesh" |
  sed -E 's/^\[mesh to SDF\] (.*): ([0-9.]+) ms \(ends at ([0-9.]+) ms\)/\3 \2 \1/' | sort -n |
  awk 'NR==1{b=$1} {printf "%8.1f %8.1f  %s\n", $1-b, $2, substr($0, index($0,$3))}' | tee -a "$OUT/summary.txt"
grep -E "^\| warm@normal" "$OUT/timeline.log" | cut -c1-150 | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
