#!/bin/bash
# GPU host: the timeline of one-call Normal runs at 1024^3 (sub2 and the armadillo, Device Auto, volume,
# --trace): the last call's phase lines sorted by when they ended (ms from its first line, duration, phase),
# to see what overlaps what (the pass, the solid check, the sharp regions). usage: OUT=dir scripts/gpu-timeline.sh
set -u
. scripts/gpu-common.sh
mkdir -p $OUT; T0=$(date +%s)
gpu_build build-gpu bench_mesh_to_sdf > /dev/null || exit 1
M=build-gpu/Testing/Benchmarks/Core/bench_mesh_to_sdf
for mesh in "sub2:.gpu/meshes/armadillo.off" ".gpu/meshes/armadillo.off"; do
  $M "$mesh" 1024 normal auto bvh volume 8 2 cold,warm@winding,warm@normal,warm@normal --trace > $OUT/t.log 2>&1
  echo "=== $mesh"; grep -E "^\| (warm|cold)" $OUT/t.log | cut -c1-110
  # the last call's lines, by end time
  n=$(grep -n "solid check beside the GPU's pass: started" $OUT/t.log | tail -1 | cut -d: -f1)
  tail -n +$((n-12)) $OUT/t.log | grep "^\[mesh" | sed -E 's/^\[mesh to SDF\] (.*): ([0-9.]+) ms \(ends at ([0-9.]+) ms\)/\3 \2 \1/' | sort -n | awk 'NR==1{b=$1} {printf "%8.1f %8.1f  %s\n", $1-b, $2, substr($0, index($0,$3))}'
done
echo "total $(( $(date +%s) - T0 )) s"
