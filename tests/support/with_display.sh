#!/usr/bin/env bash
# Runs a command on a virtual display of its own: an Xvfb that picks a free
# display number itself (-displayfd) and is stopped when the command ends,
# so that tests run at once never share a display or take down each
# other's (xvfb-run -a chooses a number before its server takes it, and two
# runs at once can end up on one server, which the first to finish stops).
# Usage: with_display.sh [-s WxHxDEPTH] COMMAND [ARGS...]  (default 640x480x24)
set -u
screen=640x480x24
if [ "${1:-}" = "-s" ]; then
  screen=$2
  shift 2
fi
number=$(mktemp)
Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3> "$number" 2> /dev/null &
xvfb=$!
trap 'kill "$xvfb" 2> /dev/null; wait "$xvfb" 2> /dev/null; rm -f "$number"' EXIT
for _ in $(seq 1 200); do  # the number is written once the server takes connections
  grep -q . "$number" && break
  kill -0 "$xvfb" 2> /dev/null || { echo "with_display: Xvfb did not start" >&2; exit 1; }
  sleep 0.05
done
grep -q . "$number" || { echo "with_display: Xvfb gave no display in 10 s" >&2; exit 1; }
DISPLAY=":$(head -n 1 "$number")" "$@"
