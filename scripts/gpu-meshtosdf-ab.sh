#!/bin/bash
# GPU-host A/B of the MeshToSdf CUDA path in one lease: builds Core alone with
# CUDA (sm_90) twice, in parallel, from a tarball of the old code (BEFORE, made
# with `git archive REV > .gpu/before.tar`) and from the working tree; runs the
# working tree's MeshToSdf CUDA, region, far-block, build, prepared-mesh and
# orientation tests (the GPU against the CPU bit for bit) and the Memory tests;
# then alternates the two builds' bench_mesh_to_sdf at 1024^3 (Device::Auto,
# dictionary volume, band 8) and ends with CUDA = CPU at 128^3 (--check-cpu).
# FOCUS picks the runs:
#   distance (default): the 13.3M-triangle sub4 of the armadillo (winding),
#     then two rounds of the paper's bunny and the armadillo (winding,
#     pseudo-normal, normal, warm one-call) and the 832k-triangle sub2; CUDA =
#     CPU on sub2 (winding) and the armadillo (pseudo-normal); sub4 --trace.
#   build: the host build; sub4 in two rounds of opposite order, sub2 and the
#     bunny, every call with --trace; sub4's host phases by the working tree's
#     bench_mesh_to_sdf_build (the old tree gets that file; where it does not
#     compile against the old code, its rows are missing); CUDA = CPU on sub2.
#   damaged: the winding sign of damaged armadillos (patch10, flip10,
#     duprev20, patch30; the clean mesh in the same round) at 512^3 and
#     1024^3 (GRIDS, e.g. GRIDS=512), two rounds of opposite order, --trace;
#     first CUDA = CPU at 128^3 for each damage (the working tree).
#   far: the Normal/PseudoNormal far blocks: two rounds of opposite order of
#     the armadillo and the paper's bunny at 1024^3 (winding, pseudo-normal,
#     normal, warm one-call; --trace splits the far kernels), then CUDA = CPU
#     at 128^3 (pseudo-normal and normal).
# AFTER_VARIANTS (optional, every focus): space-separated environment
# settings, each run as one more variant of the new build ("after:NAME=VALUE")
# in the CUDA tests and the benchmarks, for the A/B of a switch.
# No new step starts after BUDGET seconds (default 420). Logs in $OUT.
# usage: OUT=dir [FOCUS=distance|build|damaged] scripts/gpu-meshtosdf-ab.sh [BEFORE.tar] [MESHDIR=.gpu/meshes] [BUDGET]
#   MESHDIR holds armadillo.off and lvdif-bunny-30k.ply (run from the repository root)
set -u
BEFORE=${1:-.gpu/before.tar}
D=${2:-.gpu/meshes}
BUDGET=${3:-420}
FOCUS=${FOCUS:-distance}
A=$D/armadillo.off
BUNNY=$D/lvdif-bunny-30k.ply
OUT=${OUT:-out-gpu-meshtosdf-ab}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] && [ -f "$BUNNY" ] || { echo "no meshes in $D"; exit 1; }
[ -f "$BEFORE" ] || { echo "no tarball of the old code at $BEFORE"; exit 1; }
case "$FOCUS" in distance | build | damaged | far) ;; *) echo "FOCUS is distance, build, damaged or far, not $FOCUS"; exit 1 ;; esac
gpu_begin
mkdir -p /tmp/before && tar -xf "$BEFORE" -C /tmp/before
BEFORE_TARGETS=bench_mesh_to_sdf
if [ "$FOCUS" = build ]; then
  cp Testing/Benchmarks/Core/bench_mesh_to_sdf_build.cpp /tmp/before/Testing/Benchmarks/Core/
  BEFORE_TARGETS="bench_mesh_to_sdf bench_mesh_to_sdf_build"
fi
gpu_build_ab "$BEFORE_TARGETS" "bench_mesh_to_sdf bench_mesh_to_sdf_build LVDIFMeshToSdfTests LVDIFCommonTests"

TESTS='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*:MeshToSdfFarBlocks.*:MeshToSdfBuild.*:MeshToSdf.PreparedMesh*:MeshToSdfWindingFlip.OrientationIsIndependentOfThreads'
timeout 200 b-after/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter="$TESTS" > "$OUT/tests.log" 2>&1
echo "MeshToSdf tests rc=$?" | tee -a "$OUT/summary.txt"
timeout 60 b-after/Core/Common/LVDIFCommonTests --gtest_filter='Memory.*' >> "$OUT/tests.log" 2>&1
echo "Memory tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[  (PASSED|FAILED|SKIPPED) |^\[  FAILED  \]" "$OUT/tests.log" | sort -u | head -20 | tee -a "$OUT/summary.txt"
for e in ${AFTER_VARIANTS:-}; do
  env "$e" timeout 120 b-after/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter='MeshToSdfCuda.*:MeshToSdfRegion.Cuda*' \
    > "$OUT/tests-$e.log" 2>&1
  echo "MeshToSdf CUDA tests with $e rc=$? $(grep -E '^\[  (PASSED|FAILED)' "$OUT/tests-$e.log" | tr '\n' ' ')" | tee -a "$OUT/summary.txt"
done

: > "$L"
B=Testing/Benchmarks/Core
# the variants: "before", "after" and "after:NAME=VALUE" for each AFTER_VARIANTS setting
VARIANTS="before after"
for e in ${AFTER_VARIANTS:-}; do VARIANTS="$VARIANTS after:$e"; done
bench() { # bench VARIANT LIMIT ARGS...: the variant's binary, with its setting
  local v=$1 lim=$2
  shift 2
  local build=${v%%:*} setting=LVDIF_AB_VARIANT=none
  [ "$v" != "$build" ] && setting=${v#*:}
  RUN_LABEL="$v${ROUND:+ r$ROUND}" run "$lim" env "$setting" b-$build/$B/bench_mesh_to_sdf "$@"
}
reversed() { local r="" v; for v in "$@"; do r="$v $r"; done; echo $r; }
if [ "$FOCUS" = distance ]; then
  SIGNS=cold,warm@winding,warm@pseudonormal,warm@normal,warm@winding,warm@pseudonormal,warm@normal
  for v in $VARIANTS; do bench "$v" 90 "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm; done
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
elif [ "$FOCUS" = far ]; then
  SIGNS=cold,warm@winding,warm@pseudonormal,warm@normal,warm@pseudonormal,warm@normal
  for ROUND in 1 2; do
    order=$VARIANTS
    [ $ROUND = 2 ] && order=$(reversed $VARIANTS)
    for v in $order; do
      bench "$v" 60 "$A" 1024 winding auto bvh volume 8 2 "$SIGNS" --trace
      bench "$v" 60 "$BUNNY" 1024 winding auto bvh volume 8 2 "$SIGNS" --trace
    done
  done
  ROUND=
  for s in pseudonormal normal; do bench after 60 "$A" 128 $s auto bvh float 8 2 warm --check-cpu; done
  grep -E "^## |^\| (cold|warm)|^cpu check|far blocks \(|far halves|per-voxel kernel|^rc=[1-9]" "$L" | cut -c1-200 >> "$OUT/summary.txt"
elif [ "$FOCUS" = damaged ]; then
  DAMAGES="patch10 flip10 duprev20 patch30"
  # CUDA = CPU first (the working tree), then the rounds: each at both grids, the second in the other order
  for d in $DAMAGES; do bench after 40 "$d:$A" 128 winding auto bvh float 0 2 warm --check-cpu; done
  for ROUND in 1 2; do
    order=$VARIANTS
    [ $ROUND = 2 ] && order=$(reversed $VARIANTS)
    for N in ${GRIDS:-512 1024}; do for v in $order; do for d in clean $DAMAGES; do
      m="$d:$A"
      [ "$d" = clean ] && m=$A
      bench "$v" 60 "$m" $N winding auto bvh volume 8 2 cold,warm --trace
    done; done; done
  done
  ROUND=
  grep -E "^## |^\| warm|^cpu check|local step|^rc=[1-9]" "$L" | cut -c1-200 >> "$OUT/summary.txt"
  # one row per warm run: variant and round, mesh, grid, sign and end-to-end ms
  awk -F'|' '/^## / { split($2, w, " "); for (i = 1; i <= length(w); ++i) if (w[i] ~ /bench_mesh_to_sdf$/) { m = w[i + 1]; n = w[i + 2] }
      sub(/:.*/, "", m); if (m ~ /\//) m = "clean"; lab = substr($1, 4); next }
    /^\| warm / { printf "DAMAGED %-10s %-9s %5s sign %9s e2e %9s\n", lab, m, n, $7, $9 }' "$L" | tee -a "$OUT/summary.txt"
else
  # sub4 first (the open target), then sub2 and the bunny, then sub4 again in the other order
  ROUND=1
  for v in $VARIANTS; do bench "$v" 90 "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace; done
  for v in $VARIANTS; do
    bench "$v" 60 "sub2:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm --trace
    bench "$v" 40 "$BUNNY" 1024 winding auto bvh volume 8 2 cold,warm,warm,warm --trace
  done
  ROUND=2
  for v in $(reversed $VARIANTS); do bench "$v" 90 "sub4:$A" 1024 winding auto bvh volume 8 2 cold,warm,warm --trace; done
  ROUND=
  for v in before after; do
    RUN_LABEL="$v" run 90 env LVDIF_BUILD_TRACE=1 b-$v/$B/bench_mesh_to_sdf_build "sub4:$A" 1 beside,bvh,serialhead
  done
  bench after 60 "sub2:$A" 128 winding auto bvh float 0 2 warm --check-cpu
  {
    echo "## rows (ms): run | device | read | build | distance | sign | write | end-to-end"
    grep -E "^## |^\| (cold|warm) |^cpu check:|rc=[1-9]" "$L" | grep -v "^## .*bench_mesh_to_sdf_build" |
      awk -F'|' '/^\| (cold|warm) / { printf "|%s|%s|%s|%s|%s|%s|%s|%s|\n", $2, $3, $4, $5, $6, $7, $8, $9; next } { print }'
    echo "## host phases (--trace), in run order"
    grep -E "^## |\[mesh to SDF\] (prepareMesh|prepare:|mesh BVH|winding structures|upload and session)" "$L" | head -200
    echo "## host build phases of sub4 (bench_mesh_to_sdf_build, ms)"
    grep -E "^## .*bench_mesh_to_sdf_build|^\| (prepareMesh|mesh Bvh|one split)" "$L"
  } >> "$OUT/summary.txt"
fi
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
[ "$FOCUS" = damaged ] || awk -F'|' '/^## / { print substr($0, 1, 120) } /^\| (cold|warm|prepared)/ { printf "  %-24s %-5s dist %9s  e2e %9s\n", $2, $3, $6, $9 }' "$L"
