# Sourced by the GPU-host scripts (scripts/gpu-*.sh), from the repository root.
# The caller sets OUT (log folder); the budgeted ones also BUDGET (seconds after
# which no new step starts) and L (the log `run` appends to).

# Makes $OUT, starts the clock (T0) and records the machine in $OUT/machine.txt.
gpu_begin() {
  mkdir -p "$OUT"
  T0=$(date +%s)
  { date -u; nvidia-smi -L; nvcc --version | tail -2; nproc; lscpu | grep "Model name"; git log --oneline -1; } \
    > "$OUT/machine.txt" 2>&1
}

# Seconds left of the budget.
left() { echo $((BUDGET - ($(date +%s) - T0))); }

# gpu_build DIR TARGET...: Core alone with CUDA for sm_90 (Release); on failure
# prints the errors and exits. Starts $OUT/summary.txt with the build time.
gpu_build() {
  local dir=$1
  shift
  cmake -S . -B "$dir" -DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release \
    > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
  cmake --build "$dir" -j"$(nproc)" --target "$@" >> "$OUT/build.log" 2>&1 ||
    { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
  echo "build done after $(( $(date +%s) - T0 )) s" | tee "$OUT/summary.txt"
}

# gpu_build_ab "BEFORE_TARGETS" "AFTER_TARGETS": Core alone with CUDA for sm_90
# twice, in parallel on half the cores each: the old code unpacked in
# /tmp/before into b-before, the working tree into b-after; on failure prints
# the errors and exits. Starts $OUT/summary.txt with the build time.
gpu_build_ab() {
  local cfg="-DLVDIF_CORE_ONLY=ON -DLVDIF_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_BUILD_TYPE=Release"
  local half=$(( $(nproc) / 2 )) after_rc
  ( cmake -S /tmp/before -B b-before $cfg && cmake --build b-before -j"$half" --target $1 ) \
    > "$OUT/build-before.log" 2>&1 &
  ( cmake -S . -B b-after $cfg && cmake --build b-after -j"$half" --target $2 ) > "$OUT/build.log" 2>&1
  after_rc=$?
  wait
  [ "$after_rc" = 0 ] || { grep -B2 -A10 -i "error" "$OUT/build.log" | head -80; exit 1; }
  [ -x b-before/Testing/Benchmarks/Core/bench_mesh_to_sdf ] || { tail -40 "$OUT/build-before.log"; exit 1; }
  echo "builds done after $(( $(date +%s) - T0 )) s" | tee "$OUT/summary.txt"
}

# run LIMIT CMD...: skipped when the budget is spent, else limited to what is
# left; appends "## [RUN_LABEL | ]CMD (limit Ns)", the output and "rc=N" to $L
# ("## SKIPPED (budget): [RUN_LABEL | ]CMD" when skipped).
run() {
  local lim=$1
  shift
  local l head="${RUN_LABEL:+$RUN_LABEL | }$*"
  l=$(left)
  if [ "$l" -lt 10 ]; then echo "## SKIPPED (budget): $head" >> "$L"; return; fi
  [ "$lim" -gt "$l" ] && lim=$l
  echo "## $head (limit ${lim}s)" >> "$L"
  timeout "$lim" "$@" >> "$L" 2>&1
  echo "rc=$?" >> "$L"
}

# The Core subsystems that have a test executable (Core/SUB/tests builds
# LVDIF<SUB>Tests), read from the source tree so that a new one is not missed;
# none (and a message on stderr) outside the repository root.
gpu_core_subs() {
  local d
  for d in Core/*/tests; do
    [ -d "$d" ] || { echo "no Core/*/tests here: run from the repository root" >&2; return 1; }
    d=${d%/tests}
    printf "%s " "${d#Core/}"
  done
}

# gpu_core_test_targets [SUB...]: the build targets of those test executables
# (default: every subsystem's).
gpu_core_test_targets() {
  local s
  for s in ${*:-$(gpu_core_subs)}; do printf "LVDIF%sTests " "$s"; done
}

# gpu_core_tests DIR LIMIT [SUB...]: runs the Core test executables
# DIR/Core/SUB/LVDIF<SUB>Tests (default: every subsystem's), each limited to
# LIMIT seconds, its output in $OUT/LVDIF<SUB>Tests.log. One after the other:
# run at once, their OpenMP teams (16 threads each) oversubscribe the cores and
# the tests made of many tiny parallel regions crawl (MarchingCubes' table test
# ran past 150 s that way; alone it takes 2.5 s). GPU_TESTS_AT_ONCE=1 starts
# them together (the sanitizer build, slow and on a host with cores to spare).
# Prints, and appends to $OUT/summary.txt, one line per executable
# (`LVDIFEditTests rc=0 [  PASSED  ] 75 tests.`), then the failed tests' names.
# Returns 1 when an executable failed (or did not run), else 0.
gpu_core_tests() {
  local dir=$1 lim=$2 subs s n rc status=0
  local -a pids=()
  shift 2
  subs=${*:-$(gpu_core_subs)}
  [ -n "$subs" ] || return 1
  mkdir -p "$OUT"
  for s in $subs; do
    n=LVDIF${s}Tests
    rm -f "$OUT/$n.rc"
    if [ "${GPU_TESTS_AT_ONCE:-0}" = 1 ]; then
      ( timeout "$lim" "$dir/Core/$s/$n" > "$OUT/$n.log" 2>&1; echo $? > "$OUT/$n.rc" ) &
      pids+=($!)
    else
      timeout "$lim" "$dir/Core/$s/$n" > "$OUT/$n.log" 2>&1
      echo $? > "$OUT/$n.rc"
    fi
  done
  [ ${#pids[@]} = 0 ] || wait "${pids[@]}"
  for s in $subs; do
    n=LVDIF${s}Tests
    rc=$(cat "$OUT/$n.rc" 2>/dev/null || echo "none")
    [ "$rc" = 0 ] || status=1
    printf "%-26s rc=%s %s\n" "$n" "$rc" "$(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$OUT/$n.log" | tr '\n' ' ')" |
      tee -a "$OUT/summary.txt"
  done
  for s in $subs; do grep -h "^\[  FAILED  \]" "$OUT/LVDIF${s}Tests.log"; done | sort -u | head -20 | tee -a "$OUT/summary.txt"
  return $status
}

# gpu_tests_then_bench MESH: the start of the mesh-to-SDF benchmark scripts
# (gpu-solid-pn, gpu-normal-solids): checks that MESH exists, starts the clock,
# builds Core with CUDA (bench_mesh_to_sdf and every test executable), runs the
# tests, empties $L and sets M to the benchmark.
gpu_tests_then_bench() {
  [ -f "$1" ] || { echo "need $1"; exit 1; }
  gpu_begin
  gpu_build b bench_mesh_to_sdf $(gpu_core_test_targets)
  gpu_core_tests b 200
  : > "$L"
  M=b/Testing/Benchmarks/Core/bench_mesh_to_sdf
}
