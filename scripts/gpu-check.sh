#!/bin/bash
# One GPU-host session check (no VTK there): build Core with CUDA, run every
# Core test (CUDA ones included), then the GPU benchmarks of mesh to SDF
# (bunny, armadillo, dragon) and marching cubes. Logs go to $OUT.
# usage: scripts/gpu-check.sh MESHDIR   (MESHDIR holds lvdif-bunny-30k.ply and the
#        .off meshes of scripts/extract-meshes.sh; from the repository root)
set -u
M=${1:?mesh directory}
OUT=${OUT:-out-gpu}
. "$(dirname "$0")/gpu-common.sh"
mkdir -p "$OUT"
{ date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
cmake -S . -B b -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build b -j16 >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
gpu_core_tests b 240
B=b/Testing/Benchmarks/Core
L="$OUT/bench.log"
run() { echo "## $*" >> "$L"; timeout 120 "$@" >> "$L" 2>&1; echo "rc=$?" >> "$L"; }
for mesh in "$M/lvdif-bunny-30k.ply" "$M/armadillo.off" "$M/ChineseDragon-10kv.off" "$M/bunny00.off"; do
  run $B/bench_mesh_to_sdf "$mesh" 256 winding cuda bvh float
  run $B/bench_mesh_to_sdf "$mesh" 256 winding cuda bvh volume
  run $B/bench_mesh_to_sdf "$mesh" 1024 winding cuda bvh volume
done
run $B/bench_mesh_to_sdf "$M/lvdif-bunny-30k.ply" 1024 winding cuda bvh float
run $B/bench_mesh_to_sdf "$M/lvdif-bunny-30k.ply" 256 winding cpu bvh float
run $B/bench_marching_cubes 1024 3 1
echo done
