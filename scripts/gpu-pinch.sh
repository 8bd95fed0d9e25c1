#!/bin/bash
# The pinch brush on a GPU host: builds Core only with CUDA (sm_90) and runs the
# device-session comparison (EditSessionCuda.*: every brush, pinch included, on a
# device-resident session equals the CPU session; pinch runs on the synced host
# copy and hands its chunks to the device) and the brush tests (the CUDA brush
# paths, the sculpting brushes' oracles). Logs in $OUT (default ./out-gpu).
# usage (repository root): OUT=/some/dir scripts/gpu-pinch.sh
set -u
OUT=${OUT:-out-gpu}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b-pinch -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b-pinch -j"$(nproc)" --target LVDIFSessionTests LVDIFEditTests >> "$OUT/build.log" 2>&1 ||
  { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
timeout 200 b-pinch/Core/Session/LVDIFSessionTests --gtest_filter='EditSessionCuda.*' > "$OUT/session-tests.log" 2>&1
echo "LVDIFSessionTests rc=$?" | tee -a "$OUT/session-tests.log"
timeout 200 b-pinch/Core/Edit/LVDIFEditTests \
  --gtest_filter='BrushSculpt.*:BrushCuda.*:DeviceVolumeCuda.*:EditChangedBox.*' > "$OUT/edit-tests.log" 2>&1
echo "LVDIFEditTests rc=$?" | tee -a "$OUT/edit-tests.log"
grep -hE "^\[  (PASSED|FAILED|SKIPPED) " "$OUT/session-tests.log" "$OUT/edit-tests.log"
