#!/usr/bin/env bash
# Times two builds of glint on one scene, their runs interleaved so that
# both see the same machine: each run is a full trace on one thread (on one
# core where taskset is there), and the "trace" time glint prints is kept.
# Prints each build's median, fastest and slowest time, the ratio of the
# medians, and whether the two builds wrote the same bytes.
# Usage: compare_builds.sh BEFORE/glint AFTER/glint [SCENE [RUNS]]
#   SCENE defaults to scenes/room.json, RUNS to 9.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 BEFORE/glint AFTER/glint [SCENE [RUNS]]" >&2
  exit 2
fi
before=$1
after=$2
scene=${3:-scenes/room.json}
runs=${4:-9}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pin=()
if command -v taskset > /dev/null; then pin=(taskset -c 0); fi

# One full trace by BIN to OUT; prints its trace time in ms.
trace_ms() {
  local bin=$1 out=$2
  "${pin[@]}" "$bin" render "$scene" --mask all --threads 1 -o "$out" 2>&1 | sed -n 's/.*trace \([0-9.]*\) ms.*/\1/p'
}

# Median, fastest and slowest of the numbers on standard input.
summary() {
  sort -n | awk '{t[NR] = $1} END {printf "%.1f %.1f %.1f\n", t[int((NR + 1) / 2)], t[1], t[NR]}'
}

for ((i = 0; i < runs; ++i)); do
  trace_ms "$before" "$work/before.png" >> "$work/before.ms"
  trace_ms "$after" "$work/after.png" >> "$work/after.ms"
done
read -r b_med b_min b_max < <(summary < "$work/before.ms")
read -r a_med a_min a_max < <(summary < "$work/after.ms")
echo "$scene, full trace, 1 thread, $runs interleaved runs each"
echo "| build | median ms | fastest | slowest |"
echo "|---|---|---|---|"
echo "| before ($before) | $b_med | $b_min | $b_max |"
echo "| after ($after) | $a_med | $a_min | $a_max |"
awk -v a="$a_med" -v b="$b_med" 'BEGIN {printf "after / before: %.3f\n", a / b}'
if cmp -s "$work/before.png" "$work/after.png"; then echo "bytes: the same"; else echo "bytes: DIFFERENT"; fi
