#!/usr/bin/env bash
# `--png` under the command the CLI itself recommends, `xvfb-run -a` (its
# Xvfb resets when the last client leaves, unlike the test suite's -noreset
# server): every run must render. The CLI's display check used to close its
# connection right before VTK opened its own, which then met the server
# mid-reset and aborted ("bad X server connection", SIGABRT) in most runs.
# Usage: test_png_under_xvfb.sh LVDIF_EXE WORK_DIR
set -uo pipefail
exe="$(realpath "$1")"
work="$2"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing: skipped"; exit 0; }
printf 'canvas 24 40 16\nsphere 12, 20, 8, 6\n' > ball.lvs
"$exe" script ball.lvs --out ball.lvdv >/dev/null 2>&1 || { echo "FAIL: the volume was not made" >&2; exit 1; }
fails=0
for i in 1 2 3 4 5 6 7 8; do
  # a fresh server each run (the environment's DISPLAY is not used)
  env -u DISPLAY timeout -s KILL 60 xvfb-run -a "$exe" mesh ball.lvdv "m$i.ply" --png "m$i.png" >"run$i.out" 2>"run$i.err"
  rc=$?
  if [ "$rc" -ne 0 ] || [ ! -s "m$i.png" ]; then
    echo "FAIL: run $i exited with $rc: $(head -c 300 "run$i.err")" >&2
    fails=$((fails + 1))
  fi
done
[ "$fails" -eq 0 ] && echo "8 of 8 runs rendered"
exit $((fails > 0))
