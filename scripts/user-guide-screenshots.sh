#!/usr/bin/env bash
# Takes the pictures of docs/USER_GUIDE.md with the editor itself (--screenshot for
# the view, --screenshot-window for the whole window; tools picked by their keys).
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
# the whole window after one stroke
run --size 1200x780 --no-recovery --autosave 0 --new 128 --radius 6 --color "#d03020" --replay-drag "$stroke" \
  --screenshot-window "$OUT/editor-window.png"
# one picture per tool: its key, then the same stroke (radius and strength as given)
tool() { # name key extra-args...
  local name=$1 key=$2
  shift 2
  run --size 1000x700 --no-recovery --autosave 0 --new 128 --color "#d03020" --keys "$key" --replay-drag "$stroke" "$@" \
    --screenshot "$OUT/editor-tool-$name.png"
}
tool add A --radius 6
tool subtract S --radius 6
tool ctrl-add A --radius 6 --drag-modifiers ctrl
tool paint P --radius 9 --falloff smooth
tool smooth M --radius 12 --strength 1 --script docs/images/editor-bumps.lvs
tool inflate I --radius 9 --strength 0.6
tool grab G --radius 14
tool flatten T --radius 10 --strength 1
tool crease C --radius 6 --strength 1
tool symmetry A --radius 6 --mirror x
echo "pictures written to $OUT"
