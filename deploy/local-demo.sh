#!/usr/bin/env bash
# Renders the thesis's room through a glintd started on loopback for the
# occasion, then stops it: what `make demo` runs.
# Usage: deploy/local-demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out"

log=$(mktemp)
"$build/bin/glintd" --listen 127.0.0.1:0 --quiet > "$log" &
server=$!
trap 'kill "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true; rm -f "$log"' EXIT

# glintd prints "glintd: listening on 127.0.0.1:PORT, N threads" once it listens.
address=""
for _ in $(seq 1 100); do
  address=$(sed -n 's/^glintd: listening on \([^,]*\),.*/\1/p' "$log")
  [ -n "$address" ] && break
  kill -0 "$server" 2>/dev/null || { echo "glintd did not start" >&2; exit 1; }
  sleep 0.05
done
[ -n "$address" ] || { echo "glintd did not report its address" >&2; exit 1; }
echo "glintd listening on $address"

for scene in room room-gl-floor; do
  "$build/bin/glint" render "scenes/$scene.json" -o "$out/$scene.png" --mask all --server "$address"
done
echo "wrote $out/room.png and $out/room-gl-floor.png"
