#!/bin/bash
# Every Core test executable on a GPU host (CUDA tests included), built
# Core-only for sm_90, the executables one after the other; one summary line each.
# usage: scripts/gpu-core-tests.sh   (from the repository root; logs in $OUT)
set -u
OUT=${OUT:-out-gpu-tests}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -1; nproc; } > "$OUT/machine.txt" 2>&1
subs="Common Volume Formats SignFilter MeshToSdf MarchingCubes Edit Script Session"
targets=$(for s in $subs; do printf "LVDIF%sTests " "$s"; done)
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  -DLVDIF_BUILD_BENCHMARKS=OFF > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j"$(nproc)" --target $targets >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -60; exit 1; }
echo "built after ${SECONDS} s"
# one executable at a time: run at once, their OpenMP teams (16 threads each) oversubscribe the
# cores and the tests made of many tiny parallel regions crawl (MarchingCubes' table test ran past
# 150 s that way; alone it takes 2.5 s)
for s in $subs; do
  timeout 200 "b/Core/$s/LVDIF${s}Tests" > "$OUT/$s.log" 2>&1
  echo "$s rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$OUT/$s.log" | tr '\n' ' ')" >> "$OUT/summary.txt"
done
cat "$OUT/summary.txt"
grep -h "^\[  FAILED  \]" "$OUT"/*.log | sort -u | head -20
echo "done after ${SECONDS} s"
