#!/bin/bash
# GPU-host run of session 26: every Core test executable on CUDA (the memory
# limit's compare-and-swap reservation under 16 threads:
# DictionaryVolume.ConcurrentExpansionsStayWithinTheLimit, 50 repeats), then
# the armadillo at 1024^3 on CUDA into the dictionary volume, normal and
# pseudo-normal calls repeated between winding calls, to see whether the
# store's time of a normal call with the solid check beside the GPU's pass
# varies (two of four calls took 95-130 ms to store in session 26's A/B run
# against 21-35 ms for the others). No new step after BUDGET s.
# usage: OUT=dir scripts/gpu-session26.sh [ARMADILLO.off] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-420}
OUT=${OUT:-out-gpu-session26}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_tests_then_bench "$A"
b/Core/Volume/LVDIFVolumeTests --gtest_filter='DictionaryVolume.Concurrent*' --gtest_repeat=50 2>&1 |
  grep -E "^\[  (PASSED|FAILED) |Which is" | sort | uniq -c | tee -a "$OUT/summary.txt"
R=cold,warm@winding,warm@normal,warm@normal,warm@pseudonormal,warm@normal,warm@winding,warm@normal,warm@pseudonormal
R=$R,warm@normal,warm@normal,warm@winding
for round in 1 2; do
  run 60 $M "$A" 1024 normal auto bvh volume 8 2 "$R"
done
grep -E "^## |^\| (cold|warm)|rc=[1-9]" "$L" | cut -c1-150 | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
