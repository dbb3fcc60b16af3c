#!/usr/bin/env bash
# Soak test: runs birotor-sim live (1 kHz strain) and birotor-estimator on a
# private loopback udpm URL (ttl=0) for a chosen time, with birotor-soak-monitor
# counting dropped samples (seq), STRAIN->FORCE latency percentiles and the
# daemon's CPU and resident memory over time. Exit status 0 only when the
# targets hold: zero drops, memory growth after warm-up below 1 MB.
# Usage: tools/soak.sh [seconds, default 600] [--bin-dir DIR] [--port N]
#          [--prefix P] [--scenario FILE] [--out DIR] [--interval-s S]
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=600
bin_dir="${BIROTOR_BUILD_DIR:-build}"
port=7695
prefix="SOAK_$$_"  # unique per run: concurrent soaks on one host do not mix
scenario=config/scenarios/hover.yaml
out=""
interval_s=""
if [[ $# -gt 0 && "$1" != --* ]]; then seconds="$1"; shift; fi
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bin-dir) bin_dir="$2"; shift 2 ;;
    --port) port="$2"; shift 2 ;;
    --prefix) prefix="$2"; shift 2 ;;
    --scenario) scenario="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --interval-s) interval_s="$2"; shift 2 ;;
    *) echo "soak.sh: error: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[[ -n "$out" ]] || out="$bin_dir/soak-$seconds"
[[ -n "$interval_s" ]] || interval_s=$(( seconds >= 300 ? 30 : 5 ))
mkdir -p "$out"

# The newest build of a program under the build directory (targets have moved
# between folders, so an old copy may still lie around).
find_program() {
  local name="$1" path
  path=$(ls -t "$bin_dir/$name" "$bin_dir"/*/"$name" 2>/dev/null | head -1 || true)
  [[ -n "$path" && -x "$path" ]] && { echo "$path"; return; }
  echo "soak.sh: error: $name not found under $bin_dir (build it first)" >&2
  exit 2
}
estimator=$(find_program birotor-estimator)
sim=$(find_program birotor-sim)
monitor=$(find_program birotor-soak-monitor)

# Receive buffer: 4 MB if the kernel allows it (net.core.rmem_max), else its limit.
rmem_max=$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 212992)
buffer=$(( rmem_max < 4194304 ? rmem_max : 4194304 ))
port=$(( port + ${BIROTOR_TEST_PORT_OFFSET:-0} ))  # several checkouts testing at once
url="udpm://239.255.76.67:${port}?ttl=0&recv_buf_size=${buffer}"

pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM

echo "soak: ${seconds}s on $url prefix $prefix, scenario $scenario; logs in $out"
# The shipped units' real-time priorities (docs/realtime.md): a busy machine
# does not decide the drop count.
# The daemons authenticate POSE and FORCE with a site key (docs/deploy.md,
# "The site key"): this run's own, 32 random bytes only its owner reads.
site_key="$out/site.key"
rm -f "$site_key"
(umask 077 && head -c 32 /dev/urandom > "$site_key")
"$estimator" --lcm-url "$url" --prefix "$prefix" --realtime-priority 50 --site-key "$site_key" > "$out/estimator.log" 2>&1 &
estimator_pid=$!
pids+=("$estimator_pid")
sleep 1
kill -0 "$estimator_pid" 2>/dev/null || { echo "soak.sh: error: birotor-estimator did not start:" >&2; cat "$out/estimator.log" >&2; exit 2; }
"$monitor" --lcm-url "$url" --prefix "$prefix" --pid "$estimator_pid" --duration-s "$seconds" \
  --interval-s "$interval_s" --warmup-s "$(( seconds >= 60 ? 10 : 2 ))" --csv "$out/timeseries.csv" \
  > "$out/monitor.txt" 2> "$out/monitor.log" &
monitor_pid=$!
sleep 0.5
# The simulator runs a little longer than the monitor, so the monitor's whole
# window sees a steady 1 kHz stream.
"$sim" --scenario "$scenario" --lcm-url "$url" --prefix "$prefix" --log-level warn --realtime-priority 60 --site-key "$site_key" \
  --set "scenario.duration_s=$(( seconds + 5 ))" > "$out/sim.log" 2>&1 &
pids+=("$!")

status=0
wait "$monitor_pid" || status=$?
cat "$out/monitor.txt"
grep -E "receive buffer|recv_buf_size|rmem" "$out/estimator.log" | head -2 | sed 's/^/soak: daemon: /' || true
if [[ $status -eq 0 ]]; then echo "soak: PASS"; else echo "soak: FAIL (status $status)"; fi
exit $status
