#!/usr/bin/env bash
# Builds the libFuzzer targets of Testing/Fuzz (clang, ASan + UBSan), writes
# their seed corpus and runs each for a while.
#   scripts/fuzz.sh [seconds per target = 30] [build dir = build-fuzz]
# FUZZ_TARGETS="recording csv" limits the run to some targets; FUZZ_RUNS=N
# stops each after N executions instead of the time (whichever comes first).
# Longer runs: scripts/fuzz.sh 3600. Crashes are saved in <build>/crashes/;
# reproduce one with <build>/fuzz_volume_file <file>. Exit status is non-zero
# if any target found a problem.
set -euo pipefail
seconds="${1:-30}"
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${2:-$root/build-fuzz}"
jobs="${FUZZ_BUILD_JOBS:-2}"

CC="${CC:-clang}" CXX="${CXX:-clang++}" cmake -S "$root/Testing/Fuzz" -B "$build" >/dev/null
cmake --build "$build" -j "$jobs"

mkdir -p "$build/corpus/volume" "$build/corpus/bv" "$build/corpus/mesh" "$build/crashes"
"$build/make_fuzz_seeds" "$build/corpus/volume" "$build/corpus/bv" "$build/corpus/mesh"
mkdir -p "$build/corpus/script"
cp "$root"/Testing/Fuzz/corpus/script/* "$root"/Data/scripts/*.lvs "$build/corpus/script/"
for kind in recording csv socket; do
  mkdir -p "$build/corpus/$kind"
  cp "$root"/Testing/Fuzz/corpus/$kind/* "$build/corpus/$kind/"
done

status=0
targets="${FUZZ_TARGETS:-volume_file bv mesh script recording csv socket}"
for target in $targets; do
  corpus="$build/corpus/${target/volume_file/volume}"
  echo "== fuzz_$target for ${seconds}s (corpus $corpus)"
  # -rss_limit_mb: the readers must refuse absurd sizes long before this
  set +e
  "$build/fuzz_$target" "$corpus" -max_total_time="$seconds" -runs="${FUZZ_RUNS:--1}" -rss_limit_mb=1024 -malloc_limit_mb=512 \
    -artifact_prefix="$build/crashes/${target}-" -print_final_stats=1 >"$build/fuzz_$target.log" 2>&1
  rc=$?
  set -e
  tail -n 15 "$build/fuzz_$target.log"
  if [ $rc -ne 0 ]; then
    echo "!! fuzz_$target failed (exit $rc); see $build/fuzz_$target.log and $build/crashes/"
    status=1
  fi
done
exit $status
