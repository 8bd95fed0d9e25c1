#!/bin/bash
# GPU-host check of Mesh To SDF's chunk region (MeshToSdfOptions::chunkRegion,
# what a pvbatch rank computes) on CUDA: builds Core-only with CUDA (sm_90) and
# runs MeshToSdfRegion.* (every region's chunks equal the CPU's whole run, CUDA
# included) and MeshToSdfCuda.* (the CUDA route against the CPU, unchanged code).
# usage: OUT=dir scripts/gpu-meshtosdf-region.sh   (from the repository root; < 8 minutes)
set -u
OUT=${OUT:-out-gpu-meshtosdf-region}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b-region -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
timeout 360 cmake --build b-region -j"$(nproc)" --target LVDIFMeshToSdfTests \
  >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
timeout 240 b-region/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter='MeshToSdfRegion.*:MeshToSdfCuda.*' \
  > "$OUT/tests_region.log" 2>&1
echo "MeshToSdf region/CUDA tests rc=$?" | tee -a "$OUT/summary.txt"
grep -hE "^\[  (PASSED|FAILED|SKIPPED) |FAILED  \]|OK \] MeshToSdfRegion|SKIPPED \] MeshToSdfRegion" "$OUT"/tests_region.log | tee -a "$OUT/summary.txt"
