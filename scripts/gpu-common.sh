# Sourced by the budgeted GPU-host scripts (scripts/gpu-{signs,damaged,meshtosdf-ab,
# pseudonormal,meshbuild}.sh), from the repository root. The caller sets OUT
# (log folder), BUDGET (seconds after which no new step starts) and L (the log
# `run` appends to).

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
