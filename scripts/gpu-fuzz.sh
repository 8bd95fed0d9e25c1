#!/bin/bash
# Long fuzzing on a many-core host: runs the libFuzzer targets of a prebuilt
# Testing/Fuzz tree (scripts/fuzz.sh builds it: clang, ASan + UBSan) all at
# once for S seconds, each in its share of parallel workers (seeds 1..W), and
# sums the executions per target (libFuzzer's stat::number_of_executed_units).
# usage: scripts/gpu-fuzz.sh FUZZ_BUILD_DIR [seconds = 60] ["target=workers ..."]
# The build dir must hold the fuzz_* binaries and corpus/ (`scripts/fuzz.sh 1` writes both).
# Default shares favour the slow targets (bv and volume decode whole volumes,
# script runs up to 10,000 steps per input).
set -u
B=${1:?fuzz build dir}
S=${2:-60}
SHARES=${3:-"bv=6 volume_file=3 script=3 mesh=1 recording=1 csv=1 socket=1"}
OUT=${OUT:-out-fuzz}
mkdir -p "$OUT/crashes"
{ date -u; nproc; lscpu | grep "Model name"; } > "$OUT/machine.txt" 2>&1
declare -A pids
for share in $SHARES; do
  t=${share%=*}
  W=${share#*=}
  corpus="$B/corpus/${t/volume_file/volume}"
  for w in $(seq 1 "$W"); do
    "$B/fuzz_$t" "$corpus" -seed="$w" -max_total_time="$S" -rss_limit_mb=1024 -malloc_limit_mb=512 \
      -artifact_prefix="$OUT/crashes/$t-$w-" -print_final_stats=1 > "$OUT/fuzz_$t.$w.log" 2>&1 &
    pids[$t]="${pids[$t]:-} $!"
  done
done
status=0
printf "%-14s %8s %8s %12s %s\n" target workers seconds executions result | tee "$OUT/summary.txt"
for share in $SHARES; do
  t=${share%=*}
  W=${share#*=}
  bad=0
  for p in ${pids[$t]}; do wait "$p" || bad=$((bad + 1)); done
  runs=$(grep -h "stat::number_of_executed_units" "$OUT"/fuzz_$t.*.log | awk '{s += $2} END {print s + 0}')
  result=clean
  [ "$bad" -ne 0 ] && { result="$bad worker(s) failed"; status=1; }
  printf "%-14s %8s %8s %12s %s\n" "$t" "$W" "$S" "$runs" "$result" | tee -a "$OUT/summary.txt"
done
exit $status
