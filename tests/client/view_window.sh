#!/usr/bin/env bash
# glint view as a user sees it: the window on a virtual display (Xvfb, 24-bit
# colour), captured by the X server (xwd), not read back from OpenGL, holds
# the same pixels as glint render's PNG of the same scene and size, once the
# title says the frame (not the one-sample preview) is shown; under path
# transport (cornell), once its passes have summed the frame's samples, and
# with an irradiance field (cornell-field), the hybrid frame that reads it.
# Then key M, pressed four times (xdotool), steps the mask rule: after each
# press the window holds glint render --mask RULE's pixels for the rule its
# title names, the next in the cycle auto, perceptual, all, none; under path
# transport without a field (cornell) every pixel is traced under any rule,
# and the rule stays all.
# Usage: view_window.sh GLINT SCENES_DIR
# Exit 77 (CTest: skipped) without Xvfb, xwininfo, xwd, xdotool or netpbm.
set -euo pipefail
glint=$1
scenes=$2

skip() { echo "view_window: skipped: $*"; exit 77; }
command -v Xvfb > /dev/null || skip "Xvfb is not installed"
command -v xwininfo > /dev/null || skip "xwininfo (x11-utils) is not installed"
command -v xwd > /dev/null || skip "xwd (x11-apps) is not installed"
command -v xwdtopnm > /dev/null || skip "xwdtopnm (netpbm) is not installed"
command -v xdotool > /dev/null || skip "xdotool is not installed"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size=160x120
pixels=$((160 * 120 * 3))

# Each case's options beyond the size: the Cornell box's, few samples; its
# field's, few probes. A case is its scene's name, or that and "-field".
options() {
  case $1 in
    cornell) echo "--samples 16 --max-bounces 3" ;;
    cornell-field) echo "--samples 16 --max-bounces 3 --field 8,256" ;;
  esac
}
cases="room glass cornell cornell-field"
for name in $cases; do
  for rule in scene auto perceptual all none; do
    mask=""
    [ "$rule" = scene ] || mask="--mask $rule"
    # shellcheck disable=SC2046,SC2086
    "$glint" render "$scenes/${name%-field}.json" --size "$size" $(options "$name") $mask -o "$work/$name.$rule.png" -q
    pngtopnm "$work/$name.$rule.png" | tail -c "$pixels" > "$work/$name.$rule.rgb"
  done
done

# In the virtual display: for each scene, open the view, wait until its
# title says the frame is shown, capture the window and compare its pixels
# (the last WxHx3 bytes of the PPM) with the render's.
bash "$(dirname "$0")/../support/with_display.sh" bash -c '
  set -u
  glint=$1 scenes=$2 work=$3 size=$4 pixels=$5 cases=$6
  view=""
  trap "[ -n \"\$view\" ] && kill \$view 2> /dev/null; wait" EXIT
  window() { xwininfo -root -tree | grep -E "\"glint view[^\"]*\|  (frame |[0-9]+ of [0-9]+ spp)" | head -n 1 | awk "{print \$1}"; }
  options() {
    case $1 in
      cornell) echo "--samples 16 --max-bounces 3" ;;
      cornell-field) echo "--samples 16 --max-bounces 3 --field 8,256" ;;
    esac
  }
  next() {
    case $1 in auto) echo perceptual ;; perceptual) echo all ;; all) echo none ;; none) echo auto ;; esac
  }
  # Waits until the window shows $2 (the render of a rule) and its title
  # names the rule $3; 1 when it never does.
  shows() {
    name=$1 want=$2 rule=$3
    for _ in $(seq 1 300); do
      id=$(window)
      title=$(xwininfo -root -tree | grep -o "\"glint view[^\"]*\"" | head -n 1)
      if [ -n "$id" ] && [[ $title == *"|  mask $rule"* ]]; then
        xwd -silent -id "$id" | xwdtopnm 2> /dev/null | tail -c "$pixels" > "$work/$name.window.rgb"
        if cmp -s "$work/$name.window.rgb" "$want"; then return 0; fi
      fi
      sleep 0.1
    done
    echo "the window of $name never showed glint render --mask $rule'"'"'s pixels; its title: $title" >&2
    [ -s "$work/$name.window.rgb" ] && echo "its most common pixels (count, RGB): $(od -v -An -tu1 -w3 "$work/$name.window.rgb" | sort | uniq -c | sort -rn | head -n 3)" >&2
    cat "$work/$name.log" >&2
    return 1
  }
  for name in $cases; do
    "$glint" view "$scenes/${name%-field}.json" --size "$size" $(options "$name") > "$work/$name.log" 2>&1 &
    view=$!
    rule=auto
    [ "$name" = cornell ] && rule=all
    shows "$name" "$work/$name.scene.rgb" "$rule" || exit 1
    echo "view_window: the window of $name shows glint render'"'"'s pixels"
    for _ in 1 2 3 4; do
      xdotool windowfocus --sync "$(window)" key m
      [ "$name" = cornell ] || rule=$(next "$rule")
      shows "$name" "$work/$name.$rule.rgb" "$rule" || exit 1
      echo "view_window: after key M the window of $name shows glint render --mask $rule'"'"'s pixels"
    done
    kill "$view"; wait "$view" 2> /dev/null || true; view=""
  done
' bash "$glint" "$scenes" "$work" "$size" "$pixels" "$cases"
