#!/bin/bash
# The edit session on a GPU host (no VTK there): builds Core only with CUDA
# (sm_90), runs the Session, Edit and MarchingCubes tests (CUDA ones included)
# and bench_stroke_latency_core through lvdif::EditSession: GPU session at
# 512^3, 1024^3 (twice) and 2048^3, CPU session at 512^3 on 2 cores (taskset,
# three runs, and --phases on one core) and at 1024^3 on all cores, strokes of
# radius 15 and 40. Logs go to $OUT
# (default ./out-gpu). About 1.5 minutes on an H100 host with 16 cores (build 44 s).
# usage: scripts/gpu-session.sh   (from the repository root)
set -u
OUT=${OUT:-out-gpu}
. "$(dirname "$0")/gpu-common.sh"
mkdir -p "$OUT"
T0=$(date +%s)
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; free -g | head -2; } > "$OUT/machine.txt" 2>&1
J=$(nproc)
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j"$J" --target $(gpu_core_test_targets Session Edit MarchingCubes) bench_stroke_latency_core \
  >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
echo "build done after $(( $(date +%s) - T0 )) s" | tee -a "$OUT/timing.txt"
gpu_core_tests b 150 Session Edit MarchingCubes
echo "tests done after $(( $(date +%s) - T0 )) s" | tee -a "$OUT/timing.txt"
B=b/Testing/Benchmarks/Core/bench_stroke_latency_core
L="$OUT/bench.log"
: > "$L"
run() { echo "## $*" >> "$L"; timeout 100 "$@" >> "$L" 2>&1; echo "rc=$?" >> "$L"; }
run $B 512 --device cuda
run $B 1024 --device cuda
run $B 1024 --device cuda
run $B 2048 --device cuda
for i in 1 2 3; do
  run env OMP_NUM_THREADS=2 taskset -c 0,1 $B 512 --device cpu    # the 2-core CPU target, three runs
done
run env OMP_NUM_THREADS=1 taskset -c 0 $B 512 --phases             # CPU per sample: edit and re-mesh
run $B 1024 --device cpu                                            # CPU session, all cores, for reference
echo "bench done after $(( $(date +%s) - T0 )) s" | tee -a "$OUT/timing.txt"
grep -E "^\| [0-9]|^notice|^warning|rc=[1-9]|error" "$L"
