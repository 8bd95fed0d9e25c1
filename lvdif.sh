#!/usr/bin/env bash
# The two commands of the README:
#   ./lvdif.sh run    install what is missing, build, and run the demo job
#   ./lvdif.sh test   install what is missing, build, and run every test
# Options (environment): BUILD_DIR (default build), LVDIF_CUDA (AUTO|ON|OFF),
# JOBS (default: number of cores), LVDIF_SKIP_DEPS=1 to skip apt.
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$(pwd)
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
MODE=${1:-}

case "$MODE" in
  run|test|build) ;;
  *) echo "usage: $0 run|test|build" >&2; exit 2 ;;
esac

[ "${LVDIF_SKIP_DEPS:-0}" = 1 ] || bash scripts/deps.sh

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DLVDIF_CORE_ONLY=OFF \
  -DLVDIF_CUDA="${LVDIF_CUDA:-AUTO}" -DBUILD_TESTING=ON >"$BUILD_DIR.configure.log" 2>&1 ||
  { cat "$BUILD_DIR.configure.log"; exit 1; }
cmake --build "$BUILD_DIR" -j "$JOBS"

# Everything that renders needs an X server (Debian's VTK is GLX-only).
with_x() {
  if [ -n "${DISPLAY:-}" ]; then "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"; fi
}

case "$MODE" in
  run)
    mkdir -p out
    with_x "$BUILD_DIR/bin/lvdif" demo --out out
    ;;
  test)
    (cd "$BUILD_DIR" && with_x ctest --output-on-failure -j "$JOBS" --timeout 900)
    for extra in scripts/test-fuzz-smoke.sh scripts/test-paraview.sh; do
      if [ -x "$extra" ]; then echo "== $extra"; bash "$extra"; fi
    done
    echo "lvdif: all tests passed"
    ;;
esac
