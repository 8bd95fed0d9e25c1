#!/bin/bash
# The ASan + UBSan build (LVDIF_SANITIZE=ON) of Core on a many-core host
# without VTK: configure, build, and run every Core test executable; any
# sanitizer report fails the test (UBSan is fatal, ASan aborts). Logs in $OUT.
# usage: scripts/gpu-sanitize.sh   (from the repository root)
set -u
OUT=${OUT:-out-sanitize}
. "$(dirname "$0")/gpu-common.sh"
mkdir -p "$OUT"
J=$(nproc)
{ date -u; nproc; lscpu | grep "Model name"; g++ --version | head -1; } > "$OUT/machine.txt" 2>&1
cmake -S . -B bsan -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=OFF -DLVDIF_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
cmake --build bsan -j"$J" >> "$OUT/build.log" 2>&1 || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# the executables at once (each is multi-threaded; the host has the cores)
GPU_TESTS_AT_ONCE=1 gpu_core_tests bsan 500
status=$?
grep -l "ERROR: AddressSanitizer\|runtime error:\|LeakSanitizer" "$OUT"/*.log | tee "$OUT/sanitizer-reports.txt"
exit $status
