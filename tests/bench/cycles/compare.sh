#!/usr/bin/env bash
# Glint's path transport against Blender's Cycles on one scene, at equal
# samples and bounces: both render the scene to linear EXR, and glint
# compare prints their mean FLIP and RMSE; each one's time is printed. A
# second Glint frame with another seed gives the noise floor: two renders
# of one estimator differ by that much.
#   tests/bench/cycles/compare.sh [SCENE] [SIZE] [SAMPLES] [BOUNCES]
# Needs blender (make bench-deps) and a build (make build).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
scene=${1:-$root/scenes/cornell.json}
size=${2:-128}
samples=${3:-1024}
bounces=${4:-8}
glint=${GLINT:-$root/build/bin/glint}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# The scene at the size asked, as the script reads it (image size only).
python3 - "$scene" "$size" "$out/scene.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["image"]["width"] = s["image"]["height"] = int(sys.argv[2])
json.dump(s, open(sys.argv[3], "w"))
PY

frame=(--size "${size}x${size}" --samples "$samples" --pattern jittered --filter box --max-bounces "$bounces" -q)
start=$(date +%s%N)
"$glint" render "$scene" "${frame[@]}" -o "$out/glint.exr"
echo "glint: $samples samples, $bounces bounces, $((($(date +%s%N) - start) / 1000000)) ms"
"$glint" render "$scene" "${frame[@]}" --seed 1 -o "$out/glint-seed1.exr"
blender -b --factory-startup --python "$here/glint_scene.py" -- "$out/scene.json" "$out/cycles.exr" \
  "$samples" "$bounces" 2>&1 | grep '^cycles:'
echo "Cycles against Glint:"
"$glint" compare "$out/cycles.exr" "$out/glint.exr"
echo "Glint against Glint of another seed (the noise floor):"
"$glint" compare "$out/glint-seed1.exr" "$out/glint.exr"
