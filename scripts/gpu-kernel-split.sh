#!/bin/bash
# GPU-host kernel split of one bench_mesh_to_sdf configuration per line of
# CASES: builds Core alone with CUDA (sm_90), then runs each case under Nsight
# Compute with only the kernel duration metric (no replay, clocks and caches
# left alone) and prints, per case, each kernel's summed time and launches
# over the calls the bench makes. Raw CSV in $OUT.
# usage: OUT=dir scripts/gpu-kernel-split.sh MESH RES "CALLS" CASE...
#   CASE: DAMAGE (e.g. patch30, or "clean") for the winding sign, or
#   DAMAGE@SIGN for another sign mode (e.g. clean@pseudonormal);
#   e.g. scripts/gpu-kernel-split.sh .gpu/meshes/armadillo.off 512 warm,warm clean patch30 clean@pseudonormal
set -u
MESH=$1 RES=$2 CALLS=$3
shift 3
OUT=${OUT:-out-gpu-kernel-split}
BUDGET=${BUDGET:-500}
L="$OUT/bench.log"
. "$(dirname "$0")/gpu-common.sh"
gpu_begin
gpu_build b bench_mesh_to_sdf
BENCH=b/Testing/Benchmarks/Core/bench_mesh_to_sdf
for c in "$@"; do
  d=${c%@*} sign=winding
  [ "$c" != "$d" ] && sign=${c#*@}
  m=$MESH
  [ "$d" != clean ] && m="$d:$MESH"
  RUN_LABEL="plain $c" run 120 $BENCH "$m" "$RES" $sign auto bvh volume 8 2 "$CALLS" --trace
  ncu --clock-control none --cache-control none --metrics gpu__time_duration.sum --csv \
    $BENCH "$m" "$RES" $sign auto bvh volume 8 2 "$CALLS" > "$OUT/ncu-$c.csv" 2> "$OUT/ncu-$c.err"
  echo "== $c: ms per kernel over the calls $CALLS (ncu, gpu__time_duration.sum)"
  python3 - "$OUT/ncu-$c.csv" <<'PY'
import csv, sys, collections
t = collections.defaultdict(float); n = collections.Counter()
rows = [l for l in open(sys.argv[1]) if l.startswith('"')]
for r in csv.DictReader(rows):
    if r.get("Metric Name") != "gpu__time_duration.sum": continue
    v = float(r["Metric Value"].replace(",", ""))
    unit = r.get("Metric Unit", "nsecond")
    scale = {"nsecond": 1e-6, "usecond": 1e-3, "msecond": 1.0, "second": 1e3}.get(unit, 1e-6)
    k = r["Kernel Name"].split("(")[0]
    t[k] += v * scale; n[k] += 1
tot = sum(t.values())
for k, v in sorted(t.items(), key=lambda x: -x[1]):
    print(f"  {v:10.2f} ms  {100*v/tot:5.1f} %  {n[k]:6d} launches  {k}")
print(f"  {tot:10.2f} ms  total")
PY
done
grep -h "^| warm\|local step" "$L" | sort | uniq -c | head -40
