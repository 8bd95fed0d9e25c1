#!/bin/bash
# Two editors on one recovery folder: the second neither offers, discards nor
# deletes the autosave of the first, which still runs, and autosaves into a
# slot of its own; once the first is gone (killed: its lock is stale), the next
# editor offers its autosave. Before, every editor used recovery.lvdv: the
# second offered the running first one's file, and "Discard" or any normal exit
# deleted it.
# usage: RunTwoEditorsRecoveryTest.sh EDITOR DIR SIZE   (needs a display; SIZE: the window, WxH)
set -u
EDITOR=$1
DIR=$2
SIZE=$3
rm -rf "$DIR" "$DIR.volume.lvdv"
mkdir -p "$DIR"
fail() {
  echo "FAIL: $*"
  [ -n "${first:-}" ] && kill "$first" 2> /dev/null
  exit 1
}
# a volume to stand for the first editor's autosave
"$EDITOR" --new 16 --fill sphere --size "$SIZE" --no-recovery --autosave 0 --save "$DIR.volume.lvdv" ||
  fail "could not write a volume"
"$EDITOR" --recovery-dir "$DIR" --new 16 --size "$SIZE" --autosave 0 &
first=$!
# until the first editor runs: its slot's lock appears (give it 10 s at most)
for _ in $(seq 100); do
  [ -f "$DIR/recovery.lvdv.lock" ] && break
  sleep 0.1
done
cp "$DIR.volume.lvdv" "$DIR/recovery.lvdv"
"$EDITOR" --recovery-dir "$DIR" --recovery-answer discard --new 16 --size "$SIZE" --autosave 0 --quit ||
  fail "the second editor failed"
[ -f "$DIR/recovery.lvdv" ] || fail "the second editor deleted the running first editor's autosave"
kill "$first"
wait "$first" 2> /dev/null
first=
[ -f "$DIR/recovery.lvdv" ] || fail "the autosave is gone after the first editor ended abnormally"
# the first editor is gone: its autosave is offered (and discarded here)
"$EDITOR" --recovery-dir "$DIR" --recovery-answer discard --new 16 --size "$SIZE" --autosave 0 --quit ||
  fail "the third editor failed"
[ -f "$DIR/recovery.lvdv" ] && fail "the autosave of an editor that is gone was not offered"
echo "PASS"
