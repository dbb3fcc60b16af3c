#!/usr/bin/env bash
# Runs the whole suite (tools/test.sh) several times in a row with a CPU hog
# on every core beside it (stress-ng --cpu N at the normal priority), the way
# a busy vehicle computer or a shared CI machine runs it. The suite asserts no
# wall-clock figure, so it must pass every time; the flight processes of the
# live tests run SCHED_FIFO (docs/realtime.md) and are not delayed by the hog;
# a virtual machine whose host stalls the whole guest under the load is seen
# by the live tests' stall watch, which flies such a flight again.
#
# Usage: tools/test-under-load.sh [--runs N] [--hogs N] [ctest arguments]
#   --runs N   consecutive suite runs (default 3); stops at the first failure
#   --hogs N   stress-ng CPU workers (default: one per core, nproc)
# Exit status: 0 when every run passed, 1 at the first failed run, 2 on a bad
# command line. Prints one line per run (pass/fail, wall time, load average).
set -euo pipefail
cd "$(dirname "$0")/.."

runs=3
hogs=$(nproc)
ctest_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) [ $# -ge 2 ] || { echo "test-under-load: --runs needs a value" >&2; exit 2; }; runs="$2"; shift 2 ;;
    --hogs) [ $# -ge 2 ] || { echo "test-under-load: --hogs needs a value" >&2; exit 2; }; hogs="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) ctest_args+=("$1"); shift ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "test-under-load: --runs takes a whole number >= 1" >&2; exit 2; }
[[ "$hogs" =~ ^[1-9][0-9]*$ ]] || { echo "test-under-load: --hogs takes a whole number >= 1" >&2; exit 2; }

# Installs what is missing and builds (stress-ng is in tools/setup.sh's list).
tools/setup.sh
log_dir="${BIROTOR_BUILD_DIR:-build}/test-under-load"
mkdir -p "$log_dir"

hog_pid=""
stop_hog() {
  if [ -n "$hog_pid" ]; then
    kill "$hog_pid" 2>/dev/null || true
    wait "$hog_pid" 2>/dev/null || true
    hog_pid=""
  fi
}
trap stop_hog EXIT
stress-ng --cpu "$hogs" --timeout 0 --quiet > "$log_dir/stress-ng.log" 2>&1 &
hog_pid=$!
sleep 2
kill -0 "$hog_pid" 2>/dev/null || { echo "test-under-load: stress-ng did not start ($log_dir/stress-ng.log)" >&2; exit 1; }
echo "test-under-load: stress-ng --cpu $hogs (pid $hog_pid) beside $runs suite run(s); logs in $log_dir"

for run in $(seq 1 "$runs"); do
  start=$(date +%s)
  if tools/test.sh "${ctest_args[@]}" > "$log_dir/run$run.log" 2>&1; then
    verdict=passed
  else
    verdict=FAILED
  fi
  summary=$(grep -E "tests passed|tests failed" "$log_dir/run$run.log" | tail -n 1 || true)
  echo "test-under-load: run $run/$runs $verdict in $(( $(date +%s) - start )) s (${summary:-no ctest summary}); load average $(cut -d' ' -f1-3 /proc/loadavg)"
  if [ "$verdict" != passed ]; then
    grep -E "^\s+[0-9]+ - .*\((Failed|Timeout|SEGFAULT|Subprocess)" "$log_dir/run$run.log" >&2 || true
    echo "test-under-load: run $run failed; log: $log_dir/run$run.log" >&2
    exit 1
  fi
done
echo "test-under-load: $runs of $runs runs passed with $hogs CPU hog(s) beside them"
