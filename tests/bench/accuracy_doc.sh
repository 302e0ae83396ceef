#!/usr/bin/env bash
# Writes DOCS/accuracy.md from the reports `glint accuracy` wrote under
# OUT/SCENE/ (make accuracy), in the order given, copying each plot and the
# telling error images and FLIP maps it has to DOCS/images/accuracy-SCENE*.png.
# Usage: accuracy_doc.sh OUT DOCS SCENE...
set -euo pipefail
out=$1
docs=$2
shift 2
mkdir -p "$docs/images"
doc="$docs/accuracy.md"
# Copies OUT/SCENE/NAME.png to DOCS/images/accuracy-SCENE-NAME.png and prints
# its Markdown image with CAPTION, when the sweep wrote it.
picture() {
  local scene=$1 name=$2 caption=$3
  [ -f "$out/$scene/$name.png" ] || return 0
  cp "$out/$scene/$name.png" "$docs/images/accuracy-$scene-$name.png"
  printf '![%s](images/accuracy-%s-%s.png) ' "$caption" "$scene" "$name"
}
{
  echo "# What accuracy costs in time"
  echo
  echo "Written by \`make accuracy\` ($(date -u +%Y-%m-%d), $(nproc) threads): \`glint accuracy\` on the thesis's"
  echo "scenes 1 and 2 with its default sweep, each setting varied alone around the scene's own, and on the"
  echo "glass, the bunny and the bright room with the mask rules and the perceptual threshold. Every number"
  echo "can be recomputed from the PFM and PNG images the command writes (\`glint compare\`). How to read it:"
  echo "the x axis is the frame's median time, the y axis its mean FLIP against a 256-sample reference, the"
  echo "perceptual difference a viewer sees flipping between the two PNGs (Andersson et al., HPG 2020; 0 none,"
  echo "1 the most; the table gives RMSE and PSNR of the linear values too); lower left is better; the"
  echo "dashed line is the Pareto front, the circles the scene's own settings, the dotted line the FLIP of the"
  echo "reference's two halves against each other (its own noise is below it). The mask_threshold series is the"
  echo "thesis's trade-off: hybrid frames, OpenGL drawing what the threshold leaves untraced. The shadow_map"
  echo "series is the same hybrid frame with the surfaces OpenGL draws shadowed from maps of that size (0: none,"
  echo "the thesis's raster), the pixels the maps cannot decide traced. The mask_rule series sets auto against"
  echo "perceptual, and perceptual_threshold sweeps the perceptual rule's threshold ([hybrid.md](hybrid.md))."
  echo "On soft-shadows.json, light_samples sets the points each area light takes per shadow query (the"
  echo "reference takes 64 at each of its samples)."
  for scene in "$@"; do
    dir="$out/$scene"
    echo
    echo "## $scene"
    echo
    cp "$dir/accuracy.png" "$docs/images/accuracy-$scene.png"
    sed -e '1,2d' -e "s|(accuracy.png)|(images/accuracy-$scene.png)|" "$dir/report.md"
    echo
    echo "FLIP maps (black none, purple, orange, pale yellow the most) of the two mask rules, and of one sample a"
    echo "pixel, OpenGL alone and one point of each area light where the sweep has them:"
    echo
    picture "$scene" mask_rule-auto-flip "auto"
    picture "$scene" mask_rule-perceptual-flip "perceptual"
    picture "$scene" samples-1-flip "1 sample"
    picture "$scene" mask_threshold-1-flip "OpenGL only"
    picture "$scene" light_samples-1-flip "1 light sample"
    echo
  done
} > "$doc"
echo "wrote $doc"
