#!/bin/bash
# The stroke-latency GPU row: builds Core with CUDA (no VTK/Qt needed) and runs
# bench_stroke_latency_core at 1024^3 (cuda, and cpu with all threads for
# reference) plus the CUDA tests. Logs go to $OUT (default ./out-gpu).
# usage: scripts/gpu-stroke-latency.sh   (from the repository root, on the GPU host)
set -u
OUT=${OUT:-out-gpu}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nproc; uptime; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j16 --target LVDIFEditTests LVDIFMarchingCubesTests bench_stroke_latency_core >> "$OUT/build.log" 2>&1 \
  || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
B=b/Testing/Benchmarks/Core/bench_stroke_latency_core
L="$OUT/bench.log"
run() { echo "## $*" >> "$L"; timeout 90 "$@" >> "$L" 2>&1; echo "rc=$?" >> "$L"; }
for i in 1 2; do run $B 1024 --device cuda; done       # brush cpu, cuda, device; event loop, settle 6
run $B 1024 --device cuda --brush cpu --loop tick          # the VTK bench's 60 Hz loop
run $B 1024 --device cuda --brush cpu --settle 0           # no settling: the 15 ms poll collects
run $B 1024 --device cpu                                   # CPU marching cubes, all threads
run $B 1024 --device cpu --loop tick
run env OMP_NUM_THREADS=2 $B 512 --device cpu                  # the 2-core target's setting, on this host's cores
run env OMP_NUM_THREADS=2 $B 512 --device cpu --loop tick
# how long to settle: the Qt editor's 6 ms is tuned for the CPU worker
for s in 0 3 10 16; do run $B 1024 --device cuda --brush cpu --settle $s; done
run $B 1024 --device cuda --brush device --settle 10
run $B 1024 --device cpu --settle 0
run $B 512 --device cuda --brush cpu
: > "$OUT/tests_cuda.log"
for t in b/Core/Edit/LVDIFEditTests b/Core/MarchingCubes/LVDIFMarchingCubesTests; do
  timeout 100 "$t" --gtest_filter='*Cuda*' >> "$OUT/tests_cuda.log" 2>&1
  echo "tests $(basename "$t") rc=$?" >> "$OUT/tests_cuda.log"
done
tail -3 "$OUT/tests_cuda.log"
grep -v "^|--" "$L" | grep "^|\|^##\|^rc\|warning\|^volume"
