#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each, two at a time (the machine's two
# cores), from the seeds in tests/fuzz/corpus plus what earlier runs found in
# BUILD/fuzz-corpus. Prints each target's executions; exits non-zero, with
# the log and the crashing input's path, if any target finds a crash.
#   tests/fuzz/run.sh BUILD SECONDS
set -uo pipefail
build=${1:?usage: run.sh BUILD SECONDS}
seconds=${2:?usage: run.sh BUILD SECONDS}
src="$(cd "$(dirname "$0")" && pwd)"
targets=(framing session scene_json obj image mesh_blob server_link)  # as tests/fuzz/CMakeLists.txt
declare -A max_len=([framing]=65536 [session]=262144 [scene_json]=65536 [obj]=65536 [image]=65536 [mesh_blob]=65536 [server_link]=65536)

run_one() {
  local t=$1
  mkdir -p "$build/fuzz-corpus/$t" "$build/fuzz-artifacts" "$build/fuzz-logs"
  "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${max_len[$t]}" \
    -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t-" \
    "$build/fuzz-corpus/$t" "$src/corpus/$t" >"$build/fuzz-logs/$t.log" 2>&1
}

failed=0
for ((i = 0; i < ${#targets[@]}; i += 2)); do
  pids=()
  for t in "${targets[@]:i:2}"; do
    run_one "$t" &
    pids+=("$!:$t")
  done
  for entry in "${pids[@]}"; do
    pid=${entry%%:*} t=${entry#*:}
    if wait "$pid"; then
      runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$build/fuzz-logs/$t.log" | grep -o '[0-9]*$')
      cov=$(grep -o 'cov: [0-9]*' "$build/fuzz-logs/$t.log" | tail -1)
      echo "fuzz_$t: ${runs:-?} executions in ${seconds} s, ${cov:-cov: ?}, no crash"
    else
      failed=1
      echo "fuzz_$t: FAILED; its log ($build/fuzz-logs/$t.log) ends:"
      tail -40 "$build/fuzz-logs/$t.log"
      ls "$build/fuzz-artifacts/$t-"* 2>/dev/null | sed 's/^/  crashing input: /'
    fi
  done
done
exit $failed
