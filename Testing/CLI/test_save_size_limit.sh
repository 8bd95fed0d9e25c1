#!/bin/bash
# A save that fails midway never destroys the old file and fails the run: under a file size limit
# (ulimit -f; SIGXFSZ ignored, so writes fail with EFBIG as on a full disk) every mesh format of
# `lvdif mesh` and the editor's --export, --screenshot and --screenshot-window keep the old file and
# exit 1. VTK's mesh writers and QImage::save do not check their writes: the cut file was renamed over
# the old one (the editor wrote in place) and the run exited 0; so did OpenVDB's .vdb writer.
# Usage: test_save_size_limit.sh LVDIF LVDIF_EDITOR OUT (under an X display, for the editor)
set -u
lvdif=$1 editor=$2 out=$3
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
printf 'sphere 20 20 20 12\n' > s.lvs
"$lvdif" script s.lvs --size 40 --out v.lvdv > /dev/null 2>&1 || fail "the volume"
limited() { # KIB COMMAND...: the command under a file size limit of KIB KiB
  local kib=$1; shift
  bash -c 'ulimit -f "$0"; trap "" XFSZ; exec "$@"' "$kib" "$@"
}
for ext in ply obj stl vtp; do
  printf 'old file\n' > "old.$ext"
  "$lvdif" mesh v.lvdv "whole.$ext" > /dev/null 2>&1 || fail "mesh to whole.$ext"
  [ "$(stat -c %s "whole.$ext")" -gt 16384 ] || fail "whole.$ext is not over the limit: the test proves nothing"
  limited 16 "$lvdif" mesh v.lvdv "old.$ext" > "mesh-$ext.log" 2>&1
  rc=$?
  [ $rc -eq 1 ] || fail "lvdif mesh to old.$ext under the limit exited $rc: $(tail -1 "mesh-$ext.log")"
  [ "$(cat "old.$ext")" = "old file" ] || fail "old.$ext was replaced by a cut file"
  grep -q "^lvdif mesh: cannot write 'old.$ext'" "mesh-$ext.log" || fail "no error line for old.$ext: $(cat "mesh-$ext.log")"
done
# the volume formats of a command's --out alike (the OpenVDB writer, which had a rename of its own, wrote a
# cut .vdb and exited 0)
printf 'LVDIF-RECORDING 2\ncanvas 64 64 64\nend records=0\n' > c64.lvr
for ext in lvdv vti bv vdb; do
  "$lvdif" play c64.lvr --out "whole.$ext" > /dev/null 2>&1 || { echo "(no .$ext writer in this build)"; continue; }
  [ "$(stat -c %s "whole.$ext")" -gt 8192 ] || fail "whole.$ext is not over the limit: the test proves nothing"
  printf 'old file\n' > "old.$ext"
  limited 8 "$lvdif" play c64.lvr --out "old.$ext" > "play-$ext.log" 2>&1
  rc=$?
  [ $rc -eq 1 ] || fail "lvdif play --out old.$ext under the limit exited $rc: $(tail -1 "play-$ext.log")"
  [ "$(cat "old.$ext")" = "old file" ] || fail "old.$ext was replaced by a cut file"
  grep -q "^lvdif play: .*cannot write '[^']*old.$ext" "play-$ext.log" || fail "no error line for old.$ext: $(cat "play-$ext.log")"
  # one line: the .vti writer's failure was VTK's executive's dump of the request, many lines, no cause
  ! grep -q "^ \|returned failure for request\|: failed$" "play-$ext.log" || fail "not one clear error for old.$ext: $(cat "play-$ext.log")"
done
batch=(--new 64 --fill sphere --size 640x669 --no-recovery --autosave 0)
for option in --export --screenshot --screenshot-window; do
  file=old$option.png
  [ "$option" = --export ] && file=old.ply
  printf 'old file\n' > "$file"
  limited 4 "$editor" "${batch[@]}" "$option" "$file" > "editor$option.log" 2>&1
  rc=$?
  [ $rc -eq 1 ] || fail "lvdif-editor $option under the limit exited $rc: $(tail -1 "editor$option.log")"
  [ "$(cat "$file")" = "old file" ] || fail "lvdif-editor $option replaced $file by a cut file"
  grep -q "Cannot [a-z]* $file" "editor$option.log" || fail "no error line for $option: $(cat "editor$option.log")"
done
# without the limit the same saves succeed (the refusals above are the limit's)
"$editor" "${batch[@]}" --export ok.ply --screenshot ok.png > /dev/null 2>&1 || fail "the editor without the limit"
echo "safe saves OK"
