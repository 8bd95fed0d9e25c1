#!/usr/bin/env bash
# Takes the pictures of docs/USER_GUIDE.md with the editor itself (--screenshot for
# the view, --screenshot-window for the whole window; tools picked by their keys).
# usage: scripts/user-guide-screenshots.sh [build dir (default: build)]
set -euo pipefail
cd "$(dirname "$0")/.."
EDITOR="${1:-build}/bin/lvdif-editor"
OUT=docs/images
run() {
  if [ -n "${DISPLAY:-}" ]; then "$EDITOR" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$EDITOR" "$@"; fi
}
common=(--size 1000x700 --no-recovery --autosave 0)
stroke="0.36,0.52/0.42,0.55/0.48,0.57/0.54,0.585/0.60,0.595/0.66,0.60"
run "${common[@]}" --new 128 --fill sphere --radius 6 --color "#d03020" --replay-drag "$stroke" --screenshot "$OUT/editor-stroke.png"
run "${common[@]}" --new 128 --fill sphere --radius 6 --color "#d03020" --replay-drag "$stroke" --per-vertex-color --screenshot "$OUT/editor-pervertex.png"
run "${common[@]}" --script docs/images/editor-tools.lvs --screenshot "$OUT/editor-tools.png"
run "${common[@]}" --script Apps/Editor/Testing/sphere.lvs --screenshot "$OUT/editor-script.png"
run "${common[@]}" --new 128 --fill sphere --radius 6 --color "#d03020" --keys Alt+4 --replay-drag "$stroke" --screenshot "$OUT/editor-matcap.png"
# the whole window after one stroke
run --size 1200x780 --no-recovery --autosave 0 --new 128 --radius 6 --color "#d03020" --replay-drag "$stroke" \
  --screenshot-window "$OUT/editor-window.png"
# one picture per tool: its key, then the same stroke (radius and strength as given)
tool() { # name key extra-args... (DRAG=points replaces the stroke: an option is given once)
  local name=$1 key=$2
  shift 2
  run --size 1000x700 --no-recovery --autosave 0 --new 128 --color "#d03020" --keys "$key" --replay-drag "${DRAG:-$stroke}" "$@" \
    --screenshot "$OUT/editor-tool-$name.png"
}
# smooth: back and forth over the same band, four passes
zigzag="0.360,0.520/0.390,0.528/0.420,0.536/0.450,0.544/0.480,0.552/0.510,0.560/0.540,0.569/0.570,0.577/0.600,0.585/0.630,0.593/0.660,0.601/0.660,0.605/0.630,0.597/0.600,0.589/0.570,0.581/0.540,0.573/0.510,0.565/0.480,0.556/0.450,0.548/0.420,0.540/0.390,0.532/0.360,0.524/0.360,0.528/0.390,0.536/0.420,0.544/0.450,0.552/0.480,0.560/0.510,0.569/0.540,0.577/0.570,0.585/0.600,0.593/0.630,0.601/0.660,0.609/0.660,0.613/0.630,0.605/0.600,0.597/0.570,0.589/0.540,0.581/0.510,0.573/0.480,0.564/0.450,0.556/0.420,0.548/0.390,0.540/0.360,0.532"
tool add A --radius 6
tool subtract S --radius 6
tool ctrl-add A --radius 6 --drag-modifiers ctrl
tool paint P --radius 9 --falloff smooth
DRAG="$zigzag" tool smooth M --radius 12 --strength 1 --script docs/images/editor-bumps.lvs
tool inflate I --radius 9 --strength 0.6
tool grab G --radius 14
tool flatten T --radius 10 --strength 1
tool crease C --radius 6 --strength 1
tool pinch N --radius 8 --strength 1
tool symmetry A --radius 6 --mirror x
echo "pictures written to $OUT"
