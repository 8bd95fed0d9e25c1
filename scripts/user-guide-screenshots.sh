#!/usr/bin/env bash
# Takes the pictures of docs/USER_GUIDE.md with the editor itself (--screenshot).
# usage: scripts/user-guide-screenshots.sh [build dir (default: build)]
set -euo pipefail
cd "$(dirname "$0")/.."
EDITOR="${1:-build}/bin/lvdif-editor"
OUT=docs/images
run() {
  if [ -n "${DISPLAY:-}" ]; then "$EDITOR" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24" "$EDITOR" "$@"; fi
}
common=(--size 1000x700 --no-recovery --autosave 0)
stroke="0.36,0.52/0.42,0.55/0.48,0.57/0.54,0.585/0.60,0.595/0.66,0.60"
run "${common[@]}" --new 128 --fill sphere --radius 6 --color "#d03020" --replay-drag "$stroke" --screenshot "$OUT/editor-stroke.png"
run "${common[@]}" --new 128 --fill sphere --radius 6 --color "#d03020" --replay-drag "$stroke" --per-vertex-color --screenshot "$OUT/editor-pervertex.png"
run "${common[@]}" --script docs/images/editor-tools.lvs --screenshot "$OUT/editor-tools.png"
run "${common[@]}" --script Apps/Editor/Testing/sphere.lvs --screenshot "$OUT/editor-script.png"
echo "pictures written to $OUT"
