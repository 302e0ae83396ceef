#!/usr/bin/env bash
# Installs the build into a staging folder (DESTDIR) and checks that glint,
# glintd and glint-certs land in bin/ under the prefix, runnable, and the
# systemd unit beside them runs the installed glintd (its ExecStart path).
# Usage: verify_install.sh BUILD_DIR DEPLOY_DIR
set -euo pipefail
build=$1
deploy=$2
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
DESTDIR="$stage" cmake --install "$build" > "$stage/log" || { cat "$stage/log"; exit 1; }
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
for program in glint glintd glint-certs; do
  [ -x "$stage$prefix/bin/$program" ] || { echo "verify_install: $prefix/bin/$program was not installed" >&2; exit 1; }
done
"$stage$prefix/bin/glintd" --version > /dev/null
"$stage$prefix/bin/glint" --version > /dev/null
unit="$stage$prefix/lib/systemd/system/glintd@.service"
[ -f "$unit" ] || { echo "verify_install: the unit was not installed" >&2; exit 1; }
grep -q "^ExecStart=$prefix/bin/glintd " "$unit" || {
  echo "verify_install: the unit runs $(sed -n 's/^ExecStart=\([^ ]*\).*/\1/p' "$unit"), not $prefix/bin/glintd" >&2
  exit 1
}
echo "verify_install: glint, glintd, glint-certs and glintd@.service installed under $prefix"
