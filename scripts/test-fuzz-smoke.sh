#!/usr/bin/env bash
# CI's short fuzzing run: every libFuzzer target for a few seconds (about a
# minute in all, plus the sanitizer build). Longer runs: scripts/fuzz.sh 3600.
set -euo pipefail
cd "$(dirname "$0")/.."
exec bash scripts/fuzz.sh "${FUZZ_SECONDS:-12}" "${FUZZ_BUILD_DIR:-build-fuzz}"
