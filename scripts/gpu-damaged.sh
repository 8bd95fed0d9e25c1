#!/bin/bash
# GPU-host session for the winding sign of damaged meshes on CUDA (the CPU's
# construction: caps, reversed/removed faces in the dipole tree; Device::Auto
# keeps every mesh on the GPU; the decision's work lists,
# MeshToSdfCudaDipole.cuh). Builds Core-only with CUDA (sm_90), runs the
# MeshToSdfCuda tests (CUDA = CPU bit for bit on damaged meshes, with the work
# lists as they are and cut to 5 entries, without the local step of the 4^3
# blocks; the refined counts with and without it), times the clean armadillo and
# patch10, patch30, flip10, duprev20 at 512^3 (patch10 and patch30 also
# without the local step) and 1024^3 under Device::Auto
# into the dictionary volume (warm), as given and re-oriented (--reorient, at
# 1024^3), checks those damaged armadillos CUDA = CPU bit for bit at 128^3
# (float grids, both ways), and prints one table on stdout.
# Every step has a time limit; no new run starts after BUDGET seconds (default
# 300, the build included), so the script ends in about 5 minutes. Logs
# (machine, build, tests, bench, summary, table) in $OUT.
# usage: OUT=dir scripts/gpu-damaged.sh [ARMADILLO.off] [BUDGET]
#   default mesh: .gpu/meshes/armadillo.off (scripts/extract-meshes.sh makes it)
set -u
A=${1:-.gpu/meshes/armadillo.off}
BUDGET=${2:-300}
OUT=${OUT:-out-gpu-damaged}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
[ -f "$A" ] || { echo "no mesh at $A"; exit 1; }
gpu_begin
gpu_build b-damaged LVDIFMeshToSdfTests bench_mesh_to_sdf

# the CUDA tests (CUDA = CPU bit for bit on damaged meshes; their lines on stdout)
timeout 240 b-damaged/Core/MeshToSdf/LVDIFMeshToSdfTests --gtest_filter='MeshToSdfCuda.*' > "$OUT/tests.log" 2>&1
echo "MeshToSdfCuda tests rc=$?" | tee -a "$OUT/summary.txt"
grep -E "^\[ cpu vs cuda \].*(patch|flip|duprev)|^\[ local step \]|^\[  (PASSED|FAILED) |Failure" "$OUT/tests.log" | head -60 | tee -a "$OUT/summary.txt"

B=b-damaged/Testing/Benchmarks/Core/bench_mesh_to_sdf
: > "$L"
# bench LIMIT LABEL ARGS...: bench_mesh_to_sdf ARGS as `run` step LABEL (the table's row)
bench() { local lim=$1 label=$2; shift 2; RUN_LABEL=$label run "$lim" "$B" "$@"; }
DAMAGES="patch10 flip10 duprev20 patch30"
# timings: Device::Auto, dictionary volume, band 8 (cold: builds and uploads; warm: the table)
bench 30 "clean 512" "$A" 512 winding auto bvh volume 8 2 cold,warm --trace
for d in $DAMAGES; do bench 30 "$d 512" "$d:$A" 512 winding auto bvh volume 8 2 cold,warm --trace; done
# the same without the local step of the 4^3 blocks (LVDIF_CUDA_DIPOLE_LOCAL=0: the 2^3 balls, then voxel by voxel)
for d in patch10 patch30; do LVDIF_CUDA_DIPOLE_LOCAL=0 bench 30 "$d 512 no-local" "$d:$A" 512 winding auto bvh volume 8 2 cold,warm --trace; done
# CUDA = CPU bit for bit on the real damaged armadillos (128^3 float grid, no band; the CPU on all cores)
for d in $DAMAGES; do bench 30 "check $d 128" "$d:$A" 128 winding auto bvh float 0 2 warm --check-cpu; done
# the re-oriented mesh (reorientFaces, on CUDA since session 12): CUDA = CPU, then its times
for d in $DAMAGES; do bench 30 "check $d 128 reoriented" "$d:$A" 128 winding auto bvh float 0 2 warm --check-cpu --reorient; done
# 1024^3 last, patch30 last of all (a spent budget skips only that)
bench 30 "clean 1024" "$A" 1024 winding auto bvh volume 8 2 cold,warm
for d in $DAMAGES; do bench 30 "$d 1024 reoriented" "$d:$A" 1024 winding auto bvh volume 8 2 cold,warm --reorient; done
for d in $DAMAGES; do bench 60 "$d 1024" "$d:$A" 1024 winding auto bvh volume 8 2 cold,warm; done

# the table: warm end-to-end, sign time, device, ratio to the clean mesh on the same grid
awk '
  /^## SKIPPED/ { split(substr($0, 22), h, " \\| "); l = h[1]; skipped[l] = 1; order[++k] = l; next }
  /^## / { split($0, h, " \\| "); label = substr(h[1], 4); next }
  /^\| warm / { n = split($0, c, "|"); dev[label] = c[3]; sign[label] = c[7]; e2e[label] = c[9]; refined[label] = c[10]; order[++k] = label; next }
  /^cpu check:/ { chk[label] = $0; order[++k] = label; next }
  /^rc=1[0-9][0-9]/ { if (!(label in e2e) && !(label in chk)) { to[label] = 1; order[++k] = label } }
  END {
    printf "| run | device | sign ms | end-to-end ms | x clean | voxels refined / check |\n|---|---|---|---|---|---|\n"
    for (i = 1; i <= k; ++i) {
      l = order[i]; if (seen[l]++) continue
      if (l in chk) { sub(/^cpu check: /, "", chk[l]); printf "| %s | | | | | %s |\n", l, chk[l]; continue }
      if (l in to) { printf "| %s | | | timed out | | |\n", l; continue }
      if (l in skipped) { printf "| %s | | | skipped (budget) | | |\n", l; continue }
      split(l, p, " "); base = "clean " p[2]; r = (base in e2e && e2e[base] + 0 > 0) ? sprintf("%.2f", e2e[l] / e2e[base]) : ""
      printf "| %s |%s|%s|%s| %s |%s|\n", l, dev[l], sign[l], e2e[l], r, refined[l]
    }
  }' "$L" | tee "$OUT/table.md"
grep -E "winding sign on the GPU" "$L" | grep -v "local step" | sort | uniq -c | head -5
# the local step's counts per run (blocks of 4^3 expanded, failed, voxels their intervals decided)
grep -E "^## |local step" "$L" | grep -B1 "local step" | grep -v "^--" | head -40
echo "total $(( $(date +%s) - T0 )) s" | tee -a "$OUT/summary.txt"
