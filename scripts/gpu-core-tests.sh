#!/bin/bash
# Every Core test executable on a GPU host (CUDA tests included), built
# Core-only for sm_90, the executables one after the other; one summary line each.
# usage: scripts/gpu-core-tests.sh   (from the repository root; logs in $OUT)
set -u
OUT=${OUT:-out-gpu-tests}
. "$(dirname "$0")/gpu-common.sh"
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -1; nproc; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  -DLVDIF_BUILD_BENCHMARKS=OFF > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j"$(nproc)" --target $(gpu_core_test_targets) >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -60; exit 1; }
echo "built after ${SECONDS} s"
gpu_core_tests b 200
echo "done after ${SECONDS} s"
