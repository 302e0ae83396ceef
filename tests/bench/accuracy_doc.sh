#!/usr/bin/env bash
# Writes DOCS/accuracy.md from the reports `glint accuracy` wrote under
# OUT/SCENE/ (make accuracy), in the order given, copying each plot and two
# telling error images to DOCS/images/accuracy-SCENE*.png.
# Usage: accuracy_doc.sh OUT DOCS SCENE...
set -euo pipefail
out=$1
docs=$2
shift 2
mkdir -p "$docs/images"
doc="$docs/accuracy.md"
{
  echo "# What accuracy costs in time"
  echo
  echo "Written by \`make accuracy\` ($(date -u +%Y-%m-%d), $(nproc) threads): \`glint accuracy\` on the thesis's"
  echo "scenes 1 and 2 with its default sweep, each setting varied alone around the scene's own. Every"
  echo "number can be recomputed from the PFM images the command writes. How to read it: the x axis is"
  echo "the frame's median time, the y axis its RMSE against a 256-sample reference (linear values in"
  echo "[0, 1]); lower left is better; the dashed line is the Pareto front, the circles the scene's own"
  echo "settings, the dotted line the reference's own error. The mask_threshold series is the thesis's"
  echo "trade-off: hybrid frames, OpenGL drawing what the threshold leaves untraced. The shadow_map series"
  echo "is the same hybrid frame with the surfaces OpenGL draws shadowed from maps of that size (0: none, the"
  echo "thesis's raster), the pixels the maps cannot decide traced ([hybrid.md](hybrid.md))."
  for scene in "$@"; do
    dir="$out/$scene"
    echo
    echo "## $scene"
    echo
    cp "$dir/accuracy.png" "$docs/images/accuracy-$scene.png"
    cp "$dir/samples-1-error.png" "$docs/images/accuracy-$scene-samples-1-error.png"
    cp "$dir/mask_threshold-1-error.png" "$docs/images/accuracy-$scene-mask-1-error.png"
    sed -e '1,2d' -e "s|(accuracy.png)|(images/accuracy-$scene.png)|" "$dir/report.md"
    echo
    echo "Where the error is (black none, blue 1/255, green 4/255, yellow 8/255, red 32/255 and more):"
    echo "one sample per pixel (edges, the glass), and OpenGL alone (mask_threshold 1: no reflections; shadows from the maps):"
    echo
    echo "![1 sample](images/accuracy-$scene-samples-1-error.png) ![OpenGL only](images/accuracy-$scene-mask-1-error.png)"
  done
} > "$doc"
echo "wrote $doc"
