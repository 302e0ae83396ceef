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

# The thesis's Table 4.1 (640x480, 4 jittered samples, tent filter; Celeron D
# 2.66 GHz, one core): RT unit time and whole frame.
thesis_rt=(2046 878)
thesis_frame=(2068 902)
i=0
for scene in room room-gl-floor; do
  echo
  echo "== scene $((i + 1)): scenes/$scene.json (hybrid: OpenGL + ray-traced mask, through glintd)"
  "$build/bin/glint" render "scenes/$scene.json" -o "$out/$scene.png" --mask-out "$out/$scene-mask.png" \
    --frames 5 --server "$address"
  echo "  thesis (2008): RT unit ${thesis_rt[$i]} ms, frame ${thesis_frame[$i]} ms"
  i=$((i + 1))
done
echo
echo "wrote $out/room.png, $out/room-mask.png, $out/room-gl-floor.png, $out/room-gl-floor-mask.png"
