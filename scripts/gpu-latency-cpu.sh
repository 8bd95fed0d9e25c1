#!/bin/bash
# The CPU session's 2-core target on the GPU host: 512^3, strokes of radius 15
# and 40, p95 <= 33 ms (docs/BENCHMARKS.md, "The CPU session at radius 40").
# Builds Core only with CUDA (sm_90), runs the Session, Edit and MarchingCubes
# tests (the CPU = CUDA ones need the GPU), then bench_stroke_latency_core 512
# on 2 free cores (taskset -c 0,1, OMP_NUM_THREADS=2) three times, and --phases
# on one core (CPU per sample: edit, re-mesh) twice. Logs in $OUT (default
# ./out-gpu); stdout: the test summary and the benchmark rows. About 2 minutes.
# usage: scripts/gpu-latency-cpu.sh   (from the repository root)
set -u
OUT=${OUT:-out-gpu}
. "$(dirname "$0")/gpu-common.sh"
mkdir -p "$OUT"
T0=$(date +%s)
{ date -u; nvidia-smi -L; nproc; lscpu | grep "Model name"; uptime; } > "$OUT/machine.txt" 2>&1
head -2 "$OUT/machine.txt"; grep "Model name" "$OUT/machine.txt"
J=$(nproc)
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release -DLVDIF_BUILD_BENCHMARKS=ON \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j"$J" --target $(gpu_core_test_targets Session Edit MarchingCubes) bench_stroke_latency_core \
  >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -iE "error|Stop" "$OUT/build.log" | head -80; tail -5 "$OUT/build.log"; exit 1; }
gpu_core_tests b 150 Session Edit MarchingCubes
B=b/Testing/Benchmarks/Core/bench_stroke_latency_core
L="$OUT/bench.log"
: > "$L"
run() { echo "## $*" >> "$L"; timeout 120 "$@" >> "$L" 2>&1; echo "rc=$?" >> "$L"; }
uptime >> "$L"
for i in 1 2 3; do
  run env OMP_NUM_THREADS=2 taskset -c 0,1 $B 512 --device cpu --radius 15,40
done
for i in 1 2; do
  run env OMP_NUM_THREADS=1 taskset -c 0 $B 512 --phases --radius 15,40
done
uptime >> "$L"
echo "done after $(( $(date +%s) - T0 )) s"
# the rows: latency p50/p95/max are columns 7-9 of the stroke rows
grep -E "load average" "$L"   # before and after the runs
grep -E "^\| [0-9]|^warning|rc=[1-9]" "$L"
