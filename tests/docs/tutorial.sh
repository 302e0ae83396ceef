#!/bin/bash
# Runs every command of docs/tutorial.md (its ```sh blocks, in order, as one
# script) in a fresh folder beside a link to the tree's scenes, with glint
# and glintd of this build first on the PATH; then checks what the text says
# they do.
# usage: tutorial.sh BIN_DIR SOURCE_DIR
set -euo pipefail
bin=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
ln -s "$src/scenes" "$work/scenes"
{
  echo 'trap '\''kill $(jobs -p) 2>/dev/null || true'\'' EXIT'  # no glintd outlives a failed step
  awk '/^```sh$/ { on = 1; next } /^```$/ { on = 0 } on' "$src/docs/tutorial.md"
} > "$work/tutorial-commands.sh"
cd "$work"
if ! PATH="$bin:$PATH" bash -euo pipefail tutorial-commands.sh > out.log 2>&1; then
  cat out.log
  echo "tutorial.sh: a command of docs/tutorial.md failed (output above)" >&2
  exit 1
fi
cat out.log
fail() { echo "tutorial.sh: $1" >&2; exit 1; }
for f in first.png first-mask.png bunny.png bunny-stats.json bunny-near.png bunny-fit.png engine.png bunny-farm.png \
         who.png accuracy/report.md accuracy/accuracy.csv cornell-path.png cornell-field.png cornell-field-mask.png; do
  [ -s "tutorial/$f" ] || fail "the tutorial says it writes tutorial/$f; it is missing"
done
[ ! -e tutorial/broken.png ] || fail "a broken scene wrote tutorial/broken.png"
grep -qF 'glint: error: tutorial/broken.json: objects[2].radius: must be > 0' out.log ||
  fail "the broken scene's message is not the one the tutorial quotes"
grep -qF 'glint exited with 1' out.log || fail "the broken scene did not exit with 1, as the tutorial says"
grep -qF '  bounds     min (' out.log || fail "glint info printed no bounds"
grep -qF 'the same bytes as in process' out.log || fail "the farm's frame differs from the in-process one"
grep -qE '^FLIP 0\.0[0-9]+ ' out.log || fail "the Cornell box's two frames are not within the FLIP the tutorial quotes"
echo "tutorial.sh: every command ran and did what the text says"
