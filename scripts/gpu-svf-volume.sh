#!/bin/bash
# GPU-host check of the streamed sign voxel filters on a DictionaryVolume (no
# VTK there): builds Core-only with CUDA (sm_90) and runs the SignFilter and
# Volume tests (SignVoxelFilterCuda.StreamedVolumeEqualsTheCpu: the SVF2/SVF3
# slabs on the device give the CPU's voxels and statistics), then the chain
# benchmark (mesh -> volume -> clone + sign filters: time, CPU time, peaks).
# usage: OUT=dir scripts/gpu-svf-volume.sh   (from the repository root; < 8 minutes)
set -u
OUT=${OUT:-out-gpu-svf-volume}
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b-svf -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
timeout 300 cmake --build b-svf -j"$(nproc)" --target LVDIFSignFilterTests LVDIFVolumeTests bench_svf_chain \
  >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
timeout 120 b-svf/Core/SignFilter/LVDIFSignFilterTests > "$OUT/tests_signfilter.log" 2>&1
echo "SignFilter tests rc=$?" | tee -a "$OUT/summary.txt"
timeout 60 b-svf/Core/Volume/LVDIFVolumeTests > "$OUT/tests_volume.log" 2>&1
echo "Volume tests rc=$?" | tee -a "$OUT/summary.txt"
grep -hE "^\[  (PASSED|FAILED|SKIPPED) |FAILED  \]" "$OUT"/tests_*.log | tee -a "$OUT/summary.txt"
for n in 512 1024; do
  /usr/bin/time -v timeout 120 b-svf/Testing/Benchmarks/Core/bench_svf_chain $n > "$OUT/bench_$n.log" 2> "$OUT/bench_$n.time"
  grep -h BENCH "$OUT/bench_$n.log" | tee -a "$OUT/summary.txt"
  grep -h "Maximum resident" "$OUT/bench_$n.time" | tee -a "$OUT/summary.txt"
done
