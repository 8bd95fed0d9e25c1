#!/bin/bash
# The sparse volume through VTK: `lvdif mesh` against the Python chain
# reader -> vtkChunkedMarchingCubes -> .ply on the same n^3 dice file, peak RSS
# from /usr/bin/time -v. Usage: scripts/bench-sparse-chain.sh [N] [BUILD_DIR]
# (default 1024, build). Prints a table; writes work files into $TMPDIR.
set -euo pipefail
N=${1:-1024}
B=${2:-build}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=${TMPDIR:-/tmp}/lvdif-bench-sparse-$N
mkdir -p "$tmp"
sed "s/^n = 128/n = $N/" "$here/Data/scripts/dice.lvs" > "$tmp/dice.lvs"
[ -f "$tmp/dice.lvdv" ] || "$B/bin/lvdif" script "$tmp/dice.lvs" --out "$tmp/dice.lvdv" > /dev/null
measure() { # label, command...
  local label=$1; shift
  /usr/bin/time -v "$@" > "$tmp/$label.out" 2> "$tmp/$label.time"
  local wall rss
  wall=$(grep "Elapsed (wall clock)" "$tmp/$label.time" | awk '{print $NF}')
  rss=$(grep "Maximum resident set size" "$tmp/$label.time" | awk '{printf "%.0f", $NF/1024}')
  printf "| %-34s | %8s | %9s MiB |\n" "$label" "$wall" "$rss"
}
echo "dice ${N}^3: $(du -h "$tmp/dice.lvdv" | cut -f1), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
printf "| %-34s | %8s | %13s |\n" "run" "wall" "peak RSS"
measure "lvdif mesh" "$B/bin/lvdif" mesh "$tmp/dice.lvdv" "$tmp/cli.ply"
measure "python reader->ChunkedMC->ply" env PYTHONPATH="$B/lib/python3/dist-packages" /usr/bin/python3 \
  "$here/Testing/Benchmarks/Python/sparse_chain.py" "$tmp/dice.lvdv" "$tmp/python.ply"
cat "$tmp/python reader->ChunkedMC->ply.out"
tail -1 "$tmp/lvdif mesh.out"
