#!/usr/bin/env bash
# Several hosts on one machine: four network namespaces (a client and three
# servers) joined by veth pairs on 198.18.0.0/24 (the range set aside for
# network benchmarks), every link limited to 1 Gbit/s with tc tbf. A glintd
# runs in each server namespace, over mutual TLS with certificates made by
# deploy/glint-certs; the client renders the thesis's scene 1 through all
# three, known by one name with three addresses, while one glintd is killed,
# and every frame must equal the in-process frame byte for byte. Then the
# farm changes under a running render (--server-file): a fourth host listed
# before its glintd starts is retried and used once it listens, and a host
# removed from the file leaves; the image is again the in-process one.
# Traffic stays inside the namespaces.
# Usage: netns_farm.sh GLINT GLINTD SCENES_DIR
# Exit 77 (CTest: skipped) where network namespaces cannot be made.
set -euo pipefail
glint=$1
glintd=$2
scenes=$3

skip() { echo "netns_farm: skipped: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "needs root to create network namespaces"
command -v ip > /dev/null || skip "the ip command (iproute2) is not installed"
command -v tc > /dev/null || skip "the tc command (iproute2) is not installed"

tag="glint$$"
client="$tag-c"
work=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  for ns in "$client" "$tag-s0" "$tag-s1" "$tag-s2" "$tag-s3"; do ip netns del "$ns" 2>/dev/null || true; done
  rm -rf "$work" "/etc/netns/$client"
}
trap cleanup EXIT
ip netns add "$client" 2> /dev/null || skip "ip netns add failed (no permission or no kernel support)"
ip -n "$client" link set lo up

certs="$work/certs"
glint_certs="$(dirname "$0")/../../deploy/glint-certs"
"$glint_certs" "$certs" ca > /dev/null
"$glint_certs" "$certs" server glintd 198.18.0.2 198.18.0.6 198.18.0.10 198.18.0.14 glint-farm > /dev/null
"$glint_certs" "$certs" client render > /dev/null

# Server i sits at 198.18.0.(4i+2), the client's end of its link at .(4i+1);
# the glintd of hosts 0-2 start now, host 3's later.
start_glintd() {
  ip netns exec "$tag-s$1" "$glintd" --listen "${addresses[$1]}" --threads 1 --tls-cert "$certs/glintd.pem" \
    --tls-key "$certs/glintd.key" --tls-client-ca "$certs/ca.pem" > "$work/glintd$1.log" 2>&1 &
  pids+=($!)
}
addresses=()
for i in 0 1 2 3; do
  ns="$tag-s$i"
  ip netns add "$ns"
  ip -n "$ns" link set lo up
  ip link add "c$i" netns "$client" type veth peer name eth0 netns "$ns"
  ip -n "$client" addr add "198.18.0.$((4 * i + 1))/30" dev "c$i"
  ip -n "$ns" addr add "198.18.0.$((4 * i + 2))/30" dev eth0
  ip -n "$client" link set "c$i" up
  ip -n "$ns" link set eth0 up
  ip netns exec "$client" tc qdisc add dev "c$i" root tbf rate 1gbit burst 256kb latency 10ms
  ip netns exec "$ns" tc qdisc add dev eth0 root tbf rate 1gbit burst 256kb latency 10ms
  addresses+=("198.18.0.$((4 * i + 2)):7878")
done
for i in 0 1 2; do start_glintd "$i"; done
for i in 0 1 2; do
  for _ in $(seq 1 100); do
    grep -q "listening on" "$work/glintd$i.log" && break
    sleep 0.05
  done
  grep -q "listening on" "$work/glintd$i.log" || { cat "$work/glintd$i.log"; echo "glintd $i did not start" >&2; exit 1; }
done

# The client knows the three by one name with three addresses, as a
# Kubernetes headless Service or a DNS round robin would give it (ip netns
# exec puts /etc/netns/NAME/hosts over /etc/hosts).
mkdir -p "/etc/netns/$client"
for address in "${addresses[@]:0:3}"; do echo "${address%:*} glint-farm"; done > "/etc/netns/$client/hosts"

scene="$scenes/room.json"
frames=6
"$glint" render "$scene" -o "$work/reference.png" --quiet
# One glintd is killed while the client renders its frames: a moment after
# it has built the scene (the client counts it ready on the answer), not
# at a fixed time, which a slow machine's start-up outlasted (the server
# was killed before the client reached it: unreachable, not lost).
(
  for _ in $(seq 1 600); do
    grep -q ": scene .* built in" "$work/glintd1.log" && break
    sleep 0.05
  done
  sleep 0.3
  kill -9 "${pids[1]}"
) &
killer=$!
ip netns exec "$client" "$glint" render "$scene" -o "$work/farm.png" --frames "$frames" --stall-timeout 1 \
  --server glint-farm:7878 --stats "$work/stats.json" --provenance-out "$work/provenance.png" \
  --tls-ca "$certs/ca.pem" --tls-cert "$certs/render.pem" --tls-key "$certs/render.key"
wait "$killer"
wait "${pids[1]}" 2> /dev/null || true

cmp "$work/reference.png" "$work/farm.png" || { echo "the frame through three hosts differs from in process" >&2; exit 1; }
grep -q '"state":"lost"' "$work/stats.json" || { echo "the killed glintd is not reported lost" >&2; exit 1; }
for i in 0 2; do
  grep -q "\"address\":\"glint-farm:7878 (${addresses[$i]%:*})\",\"busy_ms\":[^,]*,\"bytes_in\":[1-9]" "$work/stats.json" \
    || { echo "server ${addresses[$i]} (one of glint-farm's addresses) delivered nothing" >&2; exit 1; }
done
echo "netns_farm: $frames frames through 3 namespaced glintd (mutual TLS, 1 Gbit links), one killed: identical to in process"

# The farm changes while the client renders: hosts 0, 2 and 3 listed, host
# 3's glintd started once three frames are done (glint retries it with
# backoff: 1 s, then 2 s ...), host 0 removed from the list once host 3 has
# delivered tiles.
list="$work/farm.txt"
publish() { printf '%s\n' "$@" > "$list.new" && mv "$list.new" "$list"; }
frames_done() { [ -f "$work/elastic.json" ] && wc -l < "$work/elastic.json" || echo 0; }
publish "${addresses[0]}" "${addresses[2]}" "${addresses[3]}"
elastic_frames=60
ip netns exec "$client" "$glint" render "$scene" -o "$work/elastic.png" --frames "$elastic_frames" \
  --server-file "$list" --stats "$work/elastic.json" \
  --tls-ca "$certs/ca.pem" --tls-cert "$certs/render.pem" --tls-key "$certs/render.key" --quiet &
render=$!
for _ in $(seq 1 600); do [ "$(frames_done)" -ge 3 ] && break; sleep 0.05; done
start_glintd 3
late="\"address\":\"${addresses[3]}\",\"busy_ms\":[^,]*,\"bytes_in\":[1-9]"
for _ in $(seq 1 600); do grep -q "$late" "$work/elastic.json" && break; sleep 0.05; done
publish "${addresses[2]}" "${addresses[3]}"
wait "$render" || { echo "the render through a changing farm failed" >&2; exit 1; }

cmp "$work/reference.png" "$work/elastic.png" || { echo "the frame through a changing farm differs from in process" >&2; exit 1; }
[ "$(frames_done)" -eq "$elastic_frames" ] || { echo "not every frame of the changing farm was recorded" >&2; exit 1; }
grep -q "$late" "$work/elastic.json" || { echo "the host started late delivered nothing" >&2; exit 1; }
grep -q "\"address\":\"${addresses[0]}\"[^{]*{[^}]*}[^}]*\"state\":\"left\"" "$work/elastic.json" \
  || { echo "the host removed from the list is not reported as leaving" >&2; exit 1; }
if tail -n 1 "$work/elastic.json" | grep -q "\"address\":\"${addresses[0]}\""; then
  echo "the host removed from the list is still in the last frame" >&2; exit 1
fi
echo "netns_farm: $elastic_frames frames through a changing farm (one host started late, one removed): identical to in process"
