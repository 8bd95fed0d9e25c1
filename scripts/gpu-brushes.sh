#!/bin/bash
# GPU check of the sculpting brushes: builds Core with CUDA (sm_90) and runs the
# editing tests, whose CUDA cases compare the GPU brush (Brush.cu) and the
# device-resident volume (DeviceVolume.cu) with the CPU bit for bit (strength,
# falloff, inflate, crease, flatten, soft paint, symmetry included). Logs in $OUT.
# usage (repository root): OUT=/some/dir scripts/gpu-brushes.sh
set -u
OUT=${OUT:-out-gpu}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b-brushes -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b-brushes -j16 --target LVDIFEditTests >> "$OUT/build.log" 2>&1 ||
  { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
timeout 300 b-brushes/Core/Edit/LVDIFEditTests > "$OUT/edit-tests.log" 2>&1
echo "LVDIFEditTests rc=$?" | tee -a "$OUT/edit-tests.log"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |smooth:" "$OUT/edit-tests.log"
