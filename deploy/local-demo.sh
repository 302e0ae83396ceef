#!/usr/bin/env bash
# Renders the thesis's room through two glintd started on loopback for the
# occasion (the frame's tiles shared between them), then the Cornell box
# under path transport, traced in full and as a hybrid frame that reads an
# irradiance field the two servers fill, compared by FLIP; then stops them:
# what `make demo` runs.
# Usage: deploy/local-demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out"

servers=()
logs=()
cleanup() {
  for pid in "${servers[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${servers[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -f "${logs[@]}"
}
trap cleanup EXIT

# Starts a glintd on a free loopback port and sets $address once it listens
# (glintd says "glintd: listening on 127.0.0.1:PORT, N threads, no TLS"). Not run in
# $(...): the pid must reach the cleanup.
start_glintd() {
  local log
  address=""
  log=$(mktemp)
  logs+=("$log")
  "$build/bin/glintd" --listen 127.0.0.1:0 --threads 1 --quiet --ready-fd 1 > "$log" &
  servers+=($!)
  for _ in $(seq 1 100); do
    address=$(sed -n 's/^glintd: listening on \([^,]*\),.*/\1/p' "$log")
    [ -n "$address" ] && break
    kill -0 "${servers[-1]}" 2>/dev/null || { echo "glintd did not start" >&2; exit 1; }
    sleep 0.05
  done
  [ -n "$address" ] || { echo "glintd did not report its address" >&2; exit 1; }
}

start_glintd
first=$address
start_glintd
second=$address
echo "two glintd (one thread each) listening on $first and $second"

# The thesis's Table 4.1 (640x480, 4 jittered samples, tent filter; Celeron D
# 2.66 GHz, one core): RT unit time and whole frame.
thesis_rt=(2046 878)
thesis_frame=(2068 902)
i=0
for scene in room room-gl-floor; do
  echo
  echo "== scene $((i + 1)): scenes/$scene.json (hybrid: OpenGL + ray-traced mask, tiles shared by both glintd)"
  "$build/bin/glint" render "scenes/$scene.json" -o "$out/$scene.png" --mask-out "$out/$scene-mask.png" \
    --provenance-out "$out/$scene-provenance.png" --frames 5 --server "$first,$second"
  echo "  thesis (2008): RT unit ${thesis_rt[$i]} ms, frame ${thesis_frame[$i]} ms"
  i=$((i + 1))
done

# Light between surfaces: the Cornell box path-traced, every pixel by the
# two servers; then the hybrid frame, OpenGL drawing the light of an
# irradiance field whose probes the servers fill, the tracer the rest.
cornell=(scenes/cornell.json --size 320x320 --server "$first,$second")
echo
echo "== scene 3: scenes/cornell.json, path transport, every pixel traced (tiles shared by both glintd)"
"$build/bin/glint" render "${cornell[@]}" --mask all -o "$out/cornell-path.png" \
  --provenance-out "$out/cornell-path-provenance.png"
echo
echo "== scene 3 again: the hybrid frame with an irradiance field (--field 8,256; probes and tiles shared by both glintd)"
"$build/bin/glint" render "${cornell[@]}" --field 8,256 -o "$out/cornell-field.png" \
  --mask-out "$out/cornell-field-mask.png" --provenance-out "$out/cornell-field-provenance.png"
echo "  the two frames compared (FLIP: what a viewer sees flipping between them):"
"$build/bin/glint" compare "$out/cornell-path.png" "$out/cornell-field.png" | sed 's/^/  /'
echo
echo "wrote $out/room.png, $out/room-mask.png, $out/room-provenance.png and the same for room-gl-floor;"
echo "$out/cornell-path.png, $out/cornell-field.png, their provenance pictures and the field frame's mask"
