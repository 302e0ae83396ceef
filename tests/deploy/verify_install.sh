#!/usr/bin/env bash
# Installs the build into a staging folder (DESTDIR), with the configured
# prefix and then with another given at install time (--prefix), and checks
# that glint, glintd and glint-certs land in bin/ under the prefix, runnable,
# and the systemd unit under that prefix's lib/systemd/system runs the
# installed glintd (its ExecStart path), and that nothing lands elsewhere.
# Usage: verify_install.sh BUILD_DIR DEPLOY_DIR
set -euo pipefail
build=$1
deploy=$2
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
# Installs with `prefix` (the configured one when empty) and checks it.
check() {
  local prefix=$1 dest=$2
  DESTDIR="$dest" cmake --install "$build" ${3:+--prefix "$prefix"} > "$stage/log" || { cat "$stage/log"; exit 1; }
  for program in glint glintd glint-certs; do
    [ -x "$dest$prefix/bin/$program" ] || { echo "verify_install: $prefix/bin/$program was not installed" >&2; exit 1; }
  done
  "$dest$prefix/bin/glintd" --version > /dev/null
  "$dest$prefix/bin/glint" --version > /dev/null
  local unit="$dest$prefix/lib/systemd/system/glintd@.service"
  [ -f "$unit" ] || { echo "verify_install: the unit was not installed under $prefix" >&2; exit 1; }
  grep -q "^ExecStart=$prefix/bin/glintd " "$unit" || {
    echo "verify_install: the unit runs $(sed -n 's/^ExecStart=\([^ ]*\).*/\1/p' "$unit"), not $prefix/bin/glintd" >&2
    exit 1
  }
  local strays
  strays=$(cd "$dest" && find . -type f | grep -v "^\.$prefix/" || true)
  [ -z "$strays" ] || { echo "verify_install: installed outside $prefix: $strays" >&2; exit 1; }
}
configured=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
check "$configured" "$stage/configured"
check /opt/glint-elsewhere "$stage/elsewhere" given
echo "verify_install: glint, glintd, glint-certs and glintd@.service installed under $configured, and under a prefix given at install time"
