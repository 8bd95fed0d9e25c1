#!/usr/bin/env bash
# Hostile command lines, scripts, recordings, files and paths: each must end
# with one clear line on stderr and exit status 2 (a command line refused
# before the work) or 1 (a failure while running), never a signal, within
# 30 s and 2 GiB, with the previous output file byte-identical; accepted
# hostile shapes (long chains) must succeed. Inputs are generated here.
# Progress lines ("stage: done") may precede the error line on stderr.
# Usage: test_hostile.sh LVDIF_EXE WORK_DIR
set -uo pipefail
exe="$1"
work="$2"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fails=0
note() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# run NAME EXPECT(0|1|2) NEEDLE -- command...: status, one stderr line holding NEEDLE,
# time and peak memory
run() {
  local name="$1" want="$2" needle="$3"
  shift 4
  local t0 t1 rc rss
  t0=$(date +%s.%N)
  /usr/bin/time -f "%M" -o "$name.rss" timeout -s KILL 30 "$@" >"$name.out" 2>"$name.err"
  rc=$?
  t1=$(date +%s.%N)
  rss=$(tail -n 1 "$name.rss" 2>/dev/null || echo 0)
  case "$rss" in '' | *[!0-9]*) rss=0 ;; esac
  if [ "$rc" -ne "$want" ]; then note "$name: exit $rc, expected $want; stderr: $(head -c 300 "$name.err")"; return; fi
  if [ "$rss" -gt $((2 * 1024 * 1024)) ]; then note "$name: peak RSS ${rss} KiB"; fi
  if awk "BEGIN { exit !($t1 - $t0 > 30) }"; then note "$name: took more than 30 s"; fi
  if [ "$want" -ne 0 ]; then
    # progress lines ("stage: done") may come first; the failure is one "lvdif" line
    local lines
    lines=$(grep -c '^lvdif ' "$name.err")
    if [ "$lines" -ne 1 ]; then note "$name: $lines error lines: $(head -c 300 "$name.err")"; fi
    if ! grep -qF -- "$needle" "$name.err"; then note "$name: stderr lacks '$needle': $(head -c 300 "$name.err")"; fi
  fi
}
same() { cmp -s "$1" "$2" || note "$3: $1 changed"; }

# a starting volume and outputs that must survive failures
printf 'canvas 48\nsphere 24 24 24 12\n' >base.lvs
"$exe" script base.lvs --out base.lvdv --mesh old.ply >/dev/null 2>&1 || note "cannot make base.lvdv"
cp base.lvdv base.copy && cp old.ply old.copy

# --- scripts: long chains run, deep nesting is one positioned error
python3 - <<'PY'
import random
random.seed(18)
terms = "+".join(str(random.randint(1, 9)) for _ in range(100000))
open("chain.lvs", "w").write("x = " + terms + "\nprint x\n")
open("elif.lvs", "w").write("k = 29999\nif k == 0 { x = 0 }" + "".join(
    f" else if k == {i} {{ x = {i} }}" for i in range(1, 30000)) + "\nprint x\n")
n = random.randint(1000, 100000)
open("parens.lvs", "w").write("x = " + "(" * n + "1" + ")" * n + "\n")
open("minus.lvs", "w").write("x = " + "-" * n + "1\n")
open("blocks.lvs", "w").write("if 1 {" * n + "\n")
PY
run chain 0 "" -- "$exe" script chain.lvs
run elif 0 "" -- "$exe" script elif.lvs
grep -q '^29999$' elif.out || note "elif: wrong clause: $(head -c 100 elif.out)"
for s in parens minus blocks; do run "$s" 1 "$s.lvs:1:" -- "$exe" script "$s.lvs"; grep -q "nested too deeply" "$s.err" || note "$s: $(cat "$s.err")"; done
# a script too large to lex and parse in the memory limit is refused before either
# starts, output untouched (this 4 MiB chain took about 600 MiB; a few hundred MiB
# of script ended in the out-of-memory killer)
python3 -c 'open("huge.lvs", "w").write("x = " + "1+" * (2 << 20) + "1\n")'
cp base.lvdv huge.lvdv
LVDIF_MEMORY_LIMIT=256M run hugescript 1 "lexing and parsing a script of 4.00 MiB needs" -- "$exe" script huge.lvs --out huge.lvdv
same huge.lvdv base.copy "hugescript"

# a script that fails after its last statement (an open stroke) never says "script: done"
printf 'canvas 16\nbegin\npoint 1 1 1\n' >openstroke.lvs
run openstroke 1 "openstroke.lvs:2:1: 'begin' without 'end'" -- "$exe" script openstroke.lvs
grep -q "script: done" openstroke.err && note "openstroke: 'done' before the error: $(head -c 200 openstroke.err)"

# an undo with nothing to undo is the script's error (it did nothing, and the edits were saved)
printf 'canvas 16\nsphere 8 8 8 3\ncanvas fill\nundo\n' >undo.lvs
run undoscript 1 "undo.lvs:4:1: 'undo' has nothing to undo" -- "$exe" script undo.lvs --out base.lvdv
same base.lvdv base.copy "undoscript"

# --- runaway edits and hostile numbers, refused before the work, old output untouched
for sp in 0.001 0.0037 0.01; do
  printf 'canvas 64\nspacing %s\nline 1 1 1 %s 1 1\n' "$sp" "$((RANDOM * 1000 + 100000))" >line.lvs
  run "line-$sp" 1 "line.lvs:3:1:" -- "$exe" script line.lvs --in base.lvdv --out base.lvdv
  same base.lvdv base.copy "line-$sp"
done
for cmd in "blend 1e300" "round 1e300" "radius 1e300" "spacing 1e-300" "sphere 1e300 0 0 4" "blend -1"; do
  printf 'canvas 32\n%s\nsphere 16 16 16 5\n' "$cmd" >num.lvs
  run "num-${cmd%% *}" 1 "num.lvs:" -- "$exe" script num.lvs --out base.lvdv
  same base.lvdv base.copy "num $cmd"
done

# --- recordings: positioned errors, negative radius
edit='edit time=0 op=add shape=sphere kind=basic spacing=1.6 blend=0 coloroffset=1.5 color=1,2,3,255 dabs=1'
printf 'LVDIF-RECORDING 1\n%s\nd 10 10 10 -4\n' "$edit" >neg.lvr
run neg 1 "neg.lvr:3:12: dab radius must be >= 0" -- "$exe" play neg.lvr --in base.lvdv --out base.lvdv
printf 'LVDIF-RECORDING 1\n%s\nd 10 10 1e300 4\n' "${edit/blend=0/blend=1e300}" >big.lvr
run bigblend 1 "big.lvr:2:" -- "$exe" play big.lvr --in base.lvdv --out base.lvdv
# a recording for another canvas, an undo it cannot replay, a malformed colour: one error, nothing written
printf 'LVDIF-RECORDING 1\ncanvas 999 999 999\n%s\nd 10 10 10 4\n' "$edit" >canvas.lvr
run canvas 1 "the recording was made on a 999 x 999 x 999 canvas; this volume is" -- "$exe" play canvas.lvr --in base.lvdv --out base.lvdv
printf 'LVDIF-RECORDING 1\nundo time=0\n' >undo.lvr
run undo 1 "record 1 of 1 ('undo') has nothing to undo" -- "$exe" play undo.lvr --in base.lvdv --out base.lvdv
printf 'LVDIF-RECORDING 1\n%s\nd 10 10 10 4\n' "${edit/1,2,3,255/1.5,2,3,255}" >color.lvr
run color 1 "color.lvr:2:86: color must be r,g,b,a" -- "$exe" play color.lvr --in base.lvdv --out base.lvdv
# the recording is read before the volume: its error comes first, even when --in does not exist
run recfirst 1 "neg.lvr:3:12: dab radius must be >= 0" -- "$exe" play neg.lvr --in no-such.lvdv --out base.lvdv
same base.lvdv base.copy "recordings"
# random garbage recordings and scripts: exit 0 or 1, never a signal
for i in $(seq 1 15); do
  head -c $((RANDOM % 400 + 1)) /dev/urandom >g.bin
  { echo "LVDIF-RECORDING 1"; cat g.bin; } >g.lvr
  timeout -s KILL 30 "$exe" play g.lvr --in base.lvdv >/dev/null 2>&1; rc=$?
  [ "$rc" -le 1 ] || note "garbage recording $i: exit $rc"
  { echo "canvas 16"; tr -c 'a-z0-9+*/()=\n {}.-' ' ' <g.bin; } >g.lvs
  timeout -s KILL 30 "$exe" script g.lvs >/dev/null 2>&1; rc=$?
  [ "$rc" -le 1 ] || note "garbage script $i: exit $rc"
done

# --- outputs checked before the work; failed writes are errors
for ext in ply vtp obj stl; do
  run "nodir-$ext" 2 "/nonexistent_dir" -- "$exe" mesh base.lvdv "/nonexistent_dir/x.$ext"
done
run script-mesh 2 "/nonexistent_dir" -- "$exe" script base.lvs --mesh /nonexistent_dir/x.ply
run script-out 2 "/nonexistent_dir" -- "$exe" script base.lvs --out /nonexistent_dir/x.lvdv
run badext 2 "lvdif mesh: cannot write 'x.xyz': meshes are .ply, .obj, .stl, .vtp files" -- "$exe" mesh base.lvdv x.xyz
grep -qF ';;' badext.err && note "badext: a Qt dialog filter in the message: $(cat badext.err)"
run badvolext 2 "lvdif convert: cannot write 'x.ply': volumes are .lvdv, .lvdvp, .bv, .vdb, .vti files" -- "$exe" convert base.lvdv x.ply
mkdir -p adir adir.ply
run ontodir 2 "not a regular file" -- "$exe" mesh base.lvdv adir.ply
(unset DISPLAY; run png-nodisplay 1 "no X display" -- "$exe" mesh base.lvdv old.ply --png x.png)
DISPLAY=:9876 run png-baddisplay 1 "cannot open the X display" -- "$exe" mesh base.lvdv old.ply --png x.png
same old.ply old.copy "png"

# --- files that are not regular files, without blocking
mkfifo fifo.lvdv fifo.lvs fifo.lvr fifo.ply
run info-fifo 1 "not a regular file" -- "$exe" info fifo.lvdv
run script-fifo 1 "not a regular file" -- "$exe" script fifo.lvs
run play-fifo 1 "not a regular file" -- "$exe" play fifo.lvr --in base.lvdv
run m2s-fifo 1 "not a regular file" -- "$exe" mesh-to-sdf fifo.ply x.lvdv
run info-dir 1 "not a regular file" -- "$exe" info adir
# .vdb through OpenVDB: a FIFO blocked it (opened for reading, waiting for a
# writer), a missing file said "IoError: could not open file"
mkfifo fifo.vdb
run vdb-fifo 1 "not a regular file" -- "$exe" mesh fifo.vdb x.ply
run vdb-missing 1 "cannot open 'missing.vdb': No such file" -- "$exe" convert missing.vdb x.lvdv
# a distributed volume's index (.lvdvp) is read as every file is: a FIFO blocked
# it, a folder was "empty file"; its lines are strict (comments before the magic
# line skipped the check, a stray value or a repeated key was ignored) and CRLF
# lines are read as LF ones (the piece's name ended in '\r': "cannot open")
mkdir -p pv && "$exe" convert base.lvdv pv/v.lvdvp >/dev/null 2>&1 || note "cannot write pv/v.lvdvp"
mkfifo pv/fifo.lvdvp && mkdir -p pv/dir.lvdvp
run lvdvp-fifo 1 "not a regular file" -- "$exe" convert pv/fifo.lvdvp x.lvdv
run lvdvp-dir 1 "not a regular file" -- "$exe" convert pv/dir.lvdvp x.lvdv
sed 's/$/\r/' pv/v.lvdvp >pv/crlf.lvdvp
run lvdvp-crlf 0 "" -- "$exe" convert pv/crlf.lvdvp x.lvdv
{ echo "# no magic line"; sed 1d pv/v.lvdvp; } >pv/nomagic.lvdvp
run lvdvp-nomagic 1 "line 3: not an LVDIF volume index" -- "$exe" convert pv/nomagic.lvdvp x.lvdv
sed 's/^origin .*/& 7/' pv/v.lvdvp >pv/extra.lvdvp
run lvdvp-extra 1 "origin has a value too many: '7'" -- "$exe" convert pv/extra.lvdvp x.lvdv
{ cat pv/v.lvdvp; echo "spacing 2 2 2"; } >pv/twice.lvdvp
run lvdvp-twice 1 "spacing given twice" -- "$exe" convert pv/twice.lvdvp x.lvdv
# a distributed volume's piece that cannot be written is refused before the work
# (it was found after the conversion: "piece 0: cannot write ...")
mkdir -p pv/busy_0.lvdv
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' >tet.off
run lvdvp-piece 2 "cannot write 'pv/busy_0.lvdv': a folder, not a regular file" -- "$exe" mesh-to-sdf tet.off pv/busy.lvdvp --dims 64
grep -q "mesh to SDF" lvdvp-piece.err && note "lvdvp-piece: converted before refusing: $(head -c 300 lvdvp-piece.err)"
# a garbage 3 GiB (sparse) mesh is refused after its head
printf 'garbage' >big.ply && truncate -s 3G big.ply
run bigply 1 "magic" -- "$exe" mesh-to-sdf big.ply x.lvdv

# --- saving keeps the mode and writes through a symlink
cp base.lvdv private.lvdv && chmod 600 private.lvdv
"$exe" convert base.lvdv private.lvdv >/dev/null 2>&1 || note "convert over private.lvdv failed"
[ "$(stat -c %a private.lvdv)" = 600 ] || note "mode became $(stat -c %a private.lvdv)"
ln -s private.lvdv link.lvdv
"$exe" convert base.lvdv link.lvdv >/dev/null 2>&1 || note "convert over link.lvdv failed"
[ -L link.lvdv ] || note "the symlink was replaced"
"$exe" mesh base.lvdv old.ply >/dev/null 2>&1 && chmod 640 old.ply && "$exe" mesh base.lvdv old.ply >/dev/null 2>&1
[ "$(stat -c %a old.ply)" = 640 ] || note "mesh save changed the mode to $(stat -c %a old.ply)"
ls ./*.tmp-* >/dev/null 2>&1 && note "temporary files left: $(ls ./*.tmp-*)"

# --- Ctrl-C inside one long statement and inside one long recorded edit
interrupt() {
  local name="$1"
  shift
  "$@" >"$name.out" 2>"$name.err" &
  local pid=$! t0 t1 rc
  sleep 2
  kill -INT "$pid" 2>/dev/null
  t0=$(date +%s.%N)
  wait "$pid"
  rc=$?
  t1=$(date +%s.%N)
  # 130: the CLI's "cancelled" status (an exit, not death by the signal)
  [ "$rc" -eq 130 ] || note "$name: exit $rc after Ctrl-C, expected 130: $(tail -c 200 "$name.err")"
  grep -q "cancelled" "$name.err" || note "$name: no 'cancelled' line"
  awk "BEGIN { exit !($t1 - $t0 > 5) }" && note "$name: took $(echo "$t1 - $t0" | bc) s to stop"
}
printf 'canvas 256\nradius 40\nspacing 0.002\nline 20 128 128 230 128 128\n' >slow.lvs
interrupt ctrlc-script "$exe" script slow.lvs
python3 - <<'PY'
import random
random.seed(18)
n = 200000
with open("long.lvr", "w") as f:
    f.write("LVDIF-RECORDING 1\nedit time=0 op=add shape=sphere kind=basic spacing=1.6 blend=1 "
            f"coloroffset=1.5 color=9,9,9,255 dabs={n}\n")
    for _ in range(n):
        f.write(f"d {random.uniform(4, 44):.3f} {random.uniform(4, 44):.3f} {random.uniform(4, 44):.3f} 6\n")
PY
cp base.lvdv played.lvdv && cp played.lvdv played.copy
interrupt ctrlc-play "$exe" play long.lvr --in played.lvdv --out played.lvdv
same played.lvdv played.copy "cancelled play"

if [ "$fails" -ne 0 ]; then
  echo "$fails hostile-input checks failed" >&2
  exit 1
fi
echo "hostile inputs OK"
