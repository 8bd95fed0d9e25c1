#!/bin/bash
# Ctrl-C (SIGINT) during a batch run's mesh conversion (--open-mesh) ends the
# run with status 130, as the CLI's, after one line saying it was cancelled,
# and writes nothing: it exited with 1, the status of a failure. The signal is
# sent once the conversion runs (the CLI's progress bar, which turns Ctrl-C
# into a cancel, has installed its handler: the process catches SIGINT).
# usage: RunInterruptTest.sh EDITOR CHECK DIR SIZE   (needs a display; SIZE: the window, WxH)
set -u
EDITOR=$1
CHECK=$2
DIR=$3
SIZE=$4
source "$(dirname "${BASH_SOURCE[0]}")/TestPreamble.sh"
on_fail() { [ -n "${pid:-}" ] && kill -9 "$pid" 2> /dev/null; }
"$CHECK" --write-sphere-obj "$DIR/sphere.obj" || fail "could not write the mesh"
# a conversion of many seconds: 2048 points along the sphere's axis
"$EDITOR" --open-mesh "$DIR/sphere.obj" --mesh-resolution 2048 --size "$SIZE" --no-recovery --autosave 0 \
  --save "$DIR/never.lvdv" 2> "$DIR/stderr.txt" &
pid=$!
# until the process catches SIGINT (bit 2 of SigCgt; 60 s at most)
caught=0
for _ in $(seq 600); do
  mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$pid/status" 2> /dev/null) || break
  [ -n "$mask" ] && (( (16#$mask & 2) != 0 )) && { caught=1; break; }
  sleep 0.1
done
[ "$caught" = 1 ] || fail "the editor never caught SIGINT (no conversion running?)"
kill -INT "$pid"
wait "$pid"
rc=$?
pid=
cat "$DIR/stderr.txt"
grep -q "Cannot convert .*sphere.obj: cancelled (Ctrl-C)" "$DIR/stderr.txt" ||
  fail "no line saying the conversion was cancelled (status $rc)"
[ "$rc" = 130 ] || fail "exit status $rc, not 130"
[ ! -e "$DIR/never.lvdv" ] || fail "the cancelled run wrote its --save file"
echo "cancelled with status 130"
