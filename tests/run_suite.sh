#!/usr/bin/env bash
# Runs the whole test suite (CTest) and then checks that it left nothing
# running: every process a test starts (glintd, glint view, Xvfb ...) must
# be stopped by that test. Each process the suite starts inherits a marker
# in its environment; any still alive a few seconds after CTest returns is
# named, killed, and fails the run.
# Usage: run_suite.sh BUILD_DIR JOBS
set -uo pipefail
build=$1
jobs=$2

marker="glint-suite-$$-$(date +%s%N)"
export GLINT_SUITE_RUN="$marker"
(cd "$build" && ctest --output-on-failure -j"$jobs")
rc=$?
unset GLINT_SUITE_RUN  # what this script starts from here on is not the suite's

# Processes of this run still alive, by the marker in /proc/PID/environ
# (grep reads it all: under pipefail, -q would fail the pipe with SIGPIPE).
strays() {
  for dir in /proc/[0-9]*; do
    tr '\0' '\n' 2> /dev/null < "$dir/environ" | grep -x "GLINT_SUITE_RUN=$marker" > /dev/null && echo "${dir#/proc/}"
  done
}
left=""
for _ in $(seq 1 50); do  # a test's cleanup may still be reaping
  left=$(strays)
  [ -z "$left" ] && break
  sleep 0.1
done
if [ -n "$left" ]; then
  echo "the test suite left processes running:" >&2
  for pid in $left; do
    echo "  $pid: $(tr '\0' ' ' 2> /dev/null < "/proc/$pid/cmdline")" >&2
    kill -9 "$pid" 2> /dev/null || true
  done
  exit 1
fi
exit "$rc"
