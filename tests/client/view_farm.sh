#!/usr/bin/env bash
# glint view through a farm that grows while the window waits: its title
# says how many servers are up, and a server added to the --server-file is
# up and counted within seconds, without the camera moving (no new frame is
# asked for). The window runs on a virtual display (tests/support/with_display.sh); its title is
# read with xwininfo.
# Usage: view_farm.sh GLINT GLINTD SCENES_DIR
# Exit 77 (CTest: skipped) without Xvfb or xwininfo.
set -euo pipefail
glint=$1
glintd=$2
scenes=$3

skip() { echo "view_farm: skipped: $*"; exit 77; }
command -v Xvfb > /dev/null || skip "Xvfb is not installed"
command -v xwininfo > /dev/null || skip "xwininfo (x11-utils) is not installed"

work=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2> /dev/null || true; done
  wait 2> /dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# A glintd on a free loopback port; its address in $address. Run in this
# shell, not in $(...), so that its PID reaches the cleanup.
start_glintd() {
  "$glintd" --listen 127.0.0.1:0 --threads 1 --quiet --ready-fd 1 > "$work/glintd$1.log" 2>&1 &
  pids+=($!)
  for _ in $(seq 1 100); do
    grep -q "listening on" "$work/glintd$1.log" && break
    sleep 0.05
  done
  address=$(sed -n 's/^glintd: listening on \([^,]*\).*/\1/p' "$work/glintd$1.log")
}
start_glintd 0
a=$address
start_glintd 1
b=$address
[ -n "$a" ] && [ -n "$b" ] || { echo "a glintd did not start" >&2; exit 1; }

list="$work/farm.txt"
echo "$a" > "$list"
bash "$(dirname "$0")/../support/with_display.sh" bash -c '
  set -u
  log="$2.view.log"
  "$0" view "$1" --size 160x120 --server-file "$2" > "$log" 2>&1 &
  view=$!
  title() { xwininfo -root -tree | grep -o "\"glint view[^\"]*\"" | head -n 1; }
  await() {
    for _ in $(seq 1 300); do
      title | grep -q "$1" && return 0
      sleep 0.1
    done
    echo "the title never said \"$1\"; it says: $(title)" >&2
    cat "$log" >&2
    return 1
  }
  rc=0
  await "servers 1/1 up" || rc=1
  if [ "$rc" -eq 0 ]; then
    printf "%s\n%s\n" "$3" "$4" > "$2.new" && mv "$2.new" "$2"
    await "servers 2/2 up" || rc=1
  fi
  kill "$view"
  exit "$rc"
' "$glint" "$scenes/room.json" "$list" "$a" "$b"
echo "view_farm: a server added to the list while the window waited was up and counted in its title"
