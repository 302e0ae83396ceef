#!/usr/bin/env bash
# Checks deploy/glintd@.service with systemd-analyze verify, as instance
# glintd@7878 running the glintd just built. Any complaint fails, warnings
# included. Exit 77 (CTest: skipped) where systemd-analyze is not installed.
# Usage: verify_units.sh GLINTD DEPLOY_DIR
set -euo pipefail
glintd=$1
deploy=$2
command -v systemd-analyze > /dev/null || { echo "verify_units: skipped: systemd-analyze is not installed"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed "s|/usr/local/bin/glintd|$glintd|" "$deploy/glintd@.service" > "$work/glintd@7878.service"
if ! systemd-analyze verify "$work/glintd@7878.service" > "$work/out" 2>&1 || [ -s "$work/out" ]; then
  cat "$work/out"
  echo "verify_units: deploy/glintd@.service has problems" >&2
  exit 1
fi
echo "verify_units: deploy/glintd@.service verified"
