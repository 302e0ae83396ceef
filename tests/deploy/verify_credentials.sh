#!/usr/bin/env bash
# The "a few hosts" recipe as a service would run it: deploy/glint-certs
# writes root-only keys, as installed under /etc/glint/tls; the unit runs
# glintd as an unprivileged (dynamic) user, which cannot read them. The
# drop-in deploy/glintd-tls.conf hands them over with LoadCredential. This
# test does what systemd does with it (copies each credential's file into a
# directory the service user alone can read, and sets the drop-in's
# Environment= with %d as that directory), runs glintd as user nobody with
# the unit's own command line, and renders through it with a client
# certificate; the drop-in is also checked by systemd-analyze verify with the
# unit. It first checks that nobody really cannot read the installed key.
# Usage: verify_credentials.sh GLINT GLINTD DEPLOY_DIR SCENES_DIR
# Exit 77 (CTest: skipped) where it cannot switch users (not root, no runuser).
set -euo pipefail
glint=$1
glintd=$2
deploy=$3
scenes=$4
skip() { echo "verify_credentials: skipped: $*"; exit 77; }
fail() { echo "verify_credentials: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || skip "needs root to run glintd as another user"
command -v runuser > /dev/null || skip "runuser (util-linux) is not installed"
id nobody > /dev/null 2>&1 || skip "there is no user nobody"

# Everything lives in one folder that nobody may enter (the root of /etc/glint
# on a host); the service's copy of the glintd binary sits outside it.
work=$(mktemp -d)
chmod 755 "$work"
pid=
trap '[ -n "$pid" ] && kill "$pid" 2> /dev/null; rm -rf "$work"' EXIT
etc="$work/etc/glint/tls"
"$deploy/glint-certs" "$work/certs" ca > /dev/null
"$deploy/glint-certs" "$work/certs" server render1 127.0.0.1 > /dev/null
"$deploy/glint-certs" "$work/certs" client alice > /dev/null
# The drop-in's own install steps, with /etc/glint moved into the work folder.
dropin=$(sed "s|/etc/glint/|$work/etc/glint/|g" "$deploy/glintd-tls.conf")
install -d -m 700 "$etc"
install -m 600 "$work/certs/render1.pem" "$etc/glintd.pem"
install -m 600 "$work/certs/render1.key" "$etc/glintd.key"
install -m 600 "$work/certs/ca.pem" "$etc/ca.pem"
chmod 755 "$work/etc" "$work/etc/glint"
as_nobody() { runuser -u nobody -- "$@"; }
if as_nobody cat "$etc/glintd.key" > /dev/null 2>&1; then fail "nobody can read the installed key: the test proves nothing"; fi

# systemd-analyze verify: the unit with the drop-in beside it.
if command -v systemd-analyze > /dev/null; then
  mkdir "$work/units" "$work/units/glintd@7878.service.d"
  sed "s|/usr/local/bin/glintd|$glintd|" "$deploy/glintd@.service" > "$work/units/glintd@7878.service"
  echo "$dropin" > "$work/units/glintd@7878.service.d/tls.conf"
  if ! systemd-analyze verify "$work/units/glintd@7878.service" > "$work/verify" 2>&1 || [ -s "$work/verify" ]; then
    cat "$work/verify"
    fail "deploy/glintd-tls.conf has problems"
  fi
fi

# LoadCredential=ID:PATH -> a copy at CREDENTIALS_DIRECTORY/ID owned by the
# service's user, mode 0400, in a folder only it may enter.
creds="$work/credentials"
install -d -m 700 -o nobody "$creds"
while IFS=: read -r id path; do
  install -m 400 -o nobody "$path" "$creds/$id"
done < <(echo "$dropin" | sed -n 's/^LoadCredential=//p')
environment=$(echo "$dropin" | sed -n 's/^Environment=//p' | sed "s|%d|$creds|g")
[ -n "$environment" ] || fail "the drop-in sets no Environment="

# The unit's command line, with its default environment and the drop-in's.
bin="$work/bin"
install -d -m 755 "$bin"
install -m 755 "$glintd" "$bin/glintd"
# Instance 0 (any free port); ${VAR} takes the unit's default Environment= values.
exec_start=$(sed -n 's/^ExecStart=//p' "$deploy/glintd@.service" | sed "s|/usr/local/bin/glintd|$bin/glintd|; s/%i/0/")
for setting in $(sed -n 's/^Environment=//p' "$deploy/glintd@.service"); do
  exec_start=${exec_start//\$\{${setting%%=*}\}/${setting#*=}}
done
[[ $exec_start != *'${'* ]] || fail "the unit's command line names a setting without a default: $exec_start"
# shellcheck disable=SC2086 # the command line and the environment split into words, as systemd splits them
env -i $environment "$(command -v runuser)" -u nobody -- $exec_start > "$work/glintd.log" 2>&1 &
pid=$!
for _ in $(seq 1 100); do
  grep -q "listening on" "$work/glintd.log" && break
  kill -0 "$pid" 2> /dev/null || break
  sleep 0.05
done
grep -q "listening on" "$work/glintd.log" || { cat "$work/glintd.log"; fail "glintd as nobody did not start with the credentials"; }
address=$(sed -n 's/^glintd: listening on \([^,]*\).*/\1/p' "$work/glintd.log")
"$glint" render "$scenes/room.json" -q --size 160x120 -o "$work/room.png" --server "$address" \
  --tls-ca "$work/certs/ca.pem" --tls-cert "$work/certs/alice.pem" --tls-key "$work/certs/alice.key" ||
  fail "rendering through glintd with its credentials failed"
[ -s "$work/room.png" ] || fail "no image"
echo "verify_credentials: glintd as nobody read its TLS files through the drop-in's credentials and served a frame"
