#!/bin/bash
# GPU-host run of session 27: where the store of a Normal call's write goes.
# The armadillo's normal calls at 1024^3 spent 68-134 ms storing into the
# dictionary volume in some calls and 20-35 ms in others (sessions 25-26), the
# winding calls 20-25 ms. The bench now prints each call's minor page faults;
# the same call sequence runs under the default allocator settings, with
# glibc's trimming and mmap threshold fixed (freed chunk pages kept), and with
# passive OpenMP waits (no spinning teams beside the store).
# usage: OUT=dir scripts/gpu-session27.sh [ARMADILLO.off] [BUDGET]
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-420}
OUT=${OUT:-out-gpu-session27}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "need $A"; exit 1; }
gpu_begin
gpu_build b bench_mesh_to_sdf ${EXTRA_TARGETS:-}
: > "$L"
M=b/Testing/Benchmarks/Core/bench_mesh_to_sdf
R=cold,warm@winding,warm@normal,warm@normal,warm@pseudonormal,warm@normal,warm@winding,warm@normal,warm@normal,warm@winding
KEEP="MALLOC_TRIM_THRESHOLD_=68719476736 MALLOC_MMAP_THRESHOLD_=33554432"
for mesh in "$A" "sub2:$A"; do
  RUN_LABEL=default run 90 $M "$mesh" 1024 normal auto bvh volume 8 2 "$R" --trace
  RUN_LABEL=keep-pages run 90 env $KEEP $M "$mesh" 1024 normal auto bvh volume 8 2 "$R" --trace
  RUN_LABEL=passive-omp run 90 env OMP_WAIT_POLICY=passive $M "$mesh" 1024 normal auto bvh volume 8 2 "$R" --trace
done
grep -E "^## |^\| (cold|warm)|rc=[1-9]|store into" "$L" | cut -c1-220 | tee -a "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
