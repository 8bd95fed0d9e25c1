#!/bin/bash
# GPU-host A/B of the distance pass (two kernels: runs settled or listed, the
# listed runs queried by full warps) in one lease: builds Core alone with CUDA
# (sm_90) from a tarball of the old code (BEFORE, made with `git archive REV >
# .gpu/before.tar`) and from the working tree, in parallel; runs the working
# tree's CUDA tests (the GPU against the CPU bit for bit); then alternates the
# two builds' bench_mesh_to_sdf at 1024^3 into the dictionary volume, band 8:
# the paper's bunny and the armadillo (winding, pseudo-normal, normal, warm
# one-call), the 832k-triangle sub2 and the 13.3M-triangle sub4 (winding);
# last CUDA = CPU at 128^3 (--check-cpu) on sub2 (winding) and the armadillo
# (pseudo-normal). No new step starts after BUDGET seconds (default 420).
# AFTER_VARIANTS (optional): space-separated environment settings, each run as
# one more variant of the new build ("after:NAME=VALUE") in the tests and the
# benchmarks, for the A/B of a switch.
# usage: OUT=dir scripts/gpu-distance-ab.sh [BEFORE.tar] [MESHDIR=.gpu/meshes] [BUDGET]
#   MESHDIR holds armadillo.off and lvdif-bunny-30k.ply (run from the repository root)
set -u
BEFORE=${1:-.gpu/before.tar}
D=${2:-.gpu/meshes}
BUDGET=${3:-420}
A=$D/armadillo.off
BUNNY=$D/lvdif-bunny-30k.ply
OUT=${OUT:-out-gpu-distance-ab}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] && [ -f "$BUNNY" ] || { echo "no meshes in $D"; exit 1; }
[ -f "$BEFORE" ] || { echo "no tarball of the old code at $BEFORE"; exit 1; }
gpu_begin
mkdir -p /tmp/before && tar -xf "$BEFORE" -C /tmp/before
gpu_build_ab "bench_mesh_to_sdf" "bench_mesh_to_sdf LVDIFMeshToSdfTests"

TESTS='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*:MeshToSdfFarBlocks.*:MeshToSdfBuild.*:MeshToSdf.PreparedMesh*'
timeout 200 b-after/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter="$TESTS" > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |^\[  FAILED  \]" "$OUT/tests.log" | sort -u | head -20 | tee -a "$OUT/summary.txt"
for e in ${AFTER_VARIANTS:-}; do
  env "$e" timeout 120 b-after/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*' \
    > "$OUT/tests-$e.log" 2>&1
  echo "MeshToSdf CUDA tests with $e rc=$? $(grep -E '^\[  (PASSED|FAILED)' "$OUT/tests-$e.log" | tr '\n' ' ')" | tee -a "$OUT/summary.txt"
done

: > "$L"
SIGNS=cold,warm@winding,warm@pseudonormal,warm@normal,warm@winding,warm@pseudonormal,warm@normal
# the variants: "before", "after" and "after:NAME=VALUE" for each AFTER_VARIANTS setting
VARIANTS="before after"
for e in ${AFTER_VARIANTS:-}; do VARIANTS="$VARIANTS after:$e"; done
bench() { # bench VARIANT LIMIT ARGS...: the variant's binary, with its setting
  local v=$1 lim=$2
  shift 2
  local build=${v%%:*} setting=LVDIF_AB_VARIANT=none
  [ "$v" != "$build" ] && setting=${v#*:}
  RUN_LABEL="$v${ROUND:+ r$ROUND}" run "$lim" env "$setting" b-$build/Testing/Benchmarks/Core/bench_mesh_to_sdf "$@"
}
for v in $VARIANTS; do
  bench "$v" 90 "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm
done
for ROUND in 1 2; do
  for v in $VARIANTS; do
    bench "$v" 40 "$BUNNY" 1024 winding auto bvh volume 8 2 "$SIGNS"
    bench "$v" 40 "$A" 1024 winding auto bvh volume 8 2 "$SIGNS"
    bench "$v" 60 "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm
  done
done
ROUND=
bench after 60 "sub2:$A" 128 winding auto bvh float 0 2 warm --check-cpu
bench after 60 "$A" 128 pseudonormal auto bvh float 8 2 warm --check-cpu
for e in ${AFTER_VARIANTS:-}; do bench "after:$e" 60 "$A" 128 pseudonormal auto bvh float 8 2 warm --check-cpu; done
bench after 90 "sub4:$A" 1024 winding auto bvh volume 8 2 warm --trace
grep -E "^## |^\| (cold|warm|prepared)|check|differ|^rc=[1-9]" "$L" | cut -c1-160 >> "$OUT/summary.txt"
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
awk -F'|' '/^## / { print substr($0, 1, 120) } /^\| (cold|warm|prepared)/ { printf "  %-24s %-5s dist %9s  e2e %9s\n", $2, $3, $6, $9 }' "$L"
