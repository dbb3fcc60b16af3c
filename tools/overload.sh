#!/usr/bin/env bash
# Overload measurement: one birotor-estimator on a private loopback udpm URL,
# fed by birotor-latency-probe at a sequence of strain rates (default 1 kHz,
# 20 kHz, 50 kHz, then 1 kHz again to show recovery), with
# birotor-soak-monitor recording what the daemon says it dropped
# (ESTIMATOR_STATUS: dropped_overload, missing samples from seq gaps), its CPU
# and memory. Prints one block per rate. Measures; asserts nothing.
# Usage: tools/overload.sh [seconds per rate, default 10] [--bin-dir DIR]
#          [--port N] [--rates "1000 20000 50000 1000"]
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=10
bin_dir="${BIROTOR_BUILD_DIR:-build}"
port=7696
rates="1000 20000 50000 1000"
if [[ $# -gt 0 && "$1" != --* ]]; then seconds="$1"; shift; fi
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bin-dir) bin_dir="$2"; shift 2 ;;
    --port) port="$2"; shift 2 ;;
    --rates) rates="$2"; shift 2 ;;
    *) echo "overload.sh: error: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
# The newest build of a program under the build directory (targets have moved
# between folders, so an old copy may still lie around).
find_program() {
  local name="$1" path
  path=$(ls -t "$bin_dir/$name" "$bin_dir"/*/"$name" 2>/dev/null | head -1 || true)
  [[ -n "$path" && -x "$path" ]] && { echo "$path"; return; }
  echo "overload.sh: error: $name not found under $bin_dir (build it first)" >&2
  exit 2
}
estimator=$(find_program birotor-estimator)
probe=$(find_program birotor-latency-probe)
monitor=$(find_program birotor-soak-monitor)
rmem_max=$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 212992)
buffer=$(( rmem_max < 4194304 ? rmem_max : 4194304 ))
url="udpm://239.255.76.67:${port}?ttl=0&recv_buf_size=${buffer}"
prefix="OVERLOAD_$$_"  # unique per run
out="$bin_dir/overload"
mkdir -p "$out"

pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM

# The daemons authenticate POSE and FORCE with a site key (docs/deploy.md,
# "The site key"): this run's own, 32 random bytes only its owner reads.
site_key="$out/site.key"
rm -f "$site_key"
(umask 077 && head -c 32 /dev/urandom > "$site_key")
"$estimator" --lcm-url "$url" --prefix "$prefix" --site-key "$site_key" > "$out/estimator.log" 2>&1 &
estimator_pid=$!
pids+=("$estimator_pid")
sleep 1
kill -0 "$estimator_pid" 2>/dev/null || { echo "overload.sh: error: birotor-estimator did not start:" >&2; cat "$out/estimator.log" >&2; exit 2; }
for rate in $rates; do
  echo "=== strain at ${rate} Hz for ${seconds} s ($url) ==="
  # The monitor runs until SIGINT after the probe (a probe that cannot reach
  # its rate publishes for longer than --duration-s).
  "$monitor" --lcm-url "$url" --prefix "$prefix" --pid "$estimator_pid" --duration-s 86400 \
    --interval-s 2 --warmup-s 0 --max-memory-growth-mb 1e6 > "$out/monitor-$rate.txt" 2>&1 &
  monitor_pid=$!
  sleep 0.5
  "$probe" --lcm-url "$url" --prefix "$prefix" --rate-hz "$rate" --duration-s "$seconds" --drain-s 1 \
    > "$out/probe-$rate.txt" 2>&1 || true
  sleep 1  # one more ESTIMATOR_STATUS with the final counters
  kill -INT "$monitor_pid" 2>/dev/null || true
  wait "$monitor_pid" || true
  cat "$out/probe-$rate.txt"
  grep -E "FORCE received|daemon STRAIN drops|daemon CPU|daemon RSS|processing time|ESTIMATOR_STATUS gaps" "$out/monitor-$rate.txt"
  kill -0 "$estimator_pid" 2>/dev/null && echo "daemon alive" || echo "daemon DIED"
done
grep -E "overload" "$out/estimator.log" | tail -3 || true
