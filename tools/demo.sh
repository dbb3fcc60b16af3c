#!/usr/bin/env bash
# The live demo: installs what is missing and builds (tools/setup.sh), then runs
# birotor-estimator and birotor-sim as separate processes over LCM on loopback,
# shows birotor-monitor's live view, prints the error figures, writes a PNG.
# --controller MODE adds birotor-controller: the vehicle flies closed loop on
# the three processes (e.g. tools/demo.sh --controller force_feedback thrust_loss).
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"

usage() {
  cat <<'EOF'
Usage: tools/demo.sh [options] [scenario]

Runs a scenario live: birotor-estimator and birotor-sim as two processes talking
LCM over loopback multicast (ttl=0, nothing leaves the machine), with a live view
of time, true and estimated force per rotor, thrust efficiency, status and
progress (a refreshing block on a terminal, one plain line per second otherwise).
At the end it prints the error figures (the same as
`birotor-eval --scenarios <scenario> --methods <method>`), writes
out/demo-<scenario>.png and stops both processes (SIGTERM, then wait).

  scenario            name in config/scenarios/ (default: gentle) or a .yaml path;
                      names: hover gentle aggressive thrust_loss density sensor_faults ...
  --speed X           simulated seconds per wall second (default: 1)
  --method M          ekf, inversion or motor_map (default: the one in config/estimator.yaml)
  --lcm-url URL       LCM URL (default: udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152,
                      LCM's default group and port, so tools/lcm-spy.sh without options sees
                      the demo's channels; the 2 MB receive buffer rides out scheduling
                      stalls on a busy machine, up to the kernel's net.core.rmem_max)
  --out DIR           output folder for the PNG and the process logs (default: out)
  --no-truth          the simulator publishes no TRUTH, as a real vehicle: the monitor shows
                      its vehicle view (estimates with 1 sigma, flags, input health) and a
                      summary instead of the error figures
  --controller MODE   fly closed loop through three processes: birotor-controller (MODE
                      nominal, force_feedback or mpc) publishes MOTOR_COMMAND, birotor-sim
                      --external-controller runs it as the vehicle's ESCs; the flight is
                      recorded (lcm-logger) and its figures printed: position held,
                      commands, fallbacks with their times (birotor-review, which also
                      writes <out>/demo-<scenario>-review.html); in real time only (--speed 1)
  --vehicle FILE      a vehicle description with N arms (e.g. config/vehicles/trirotor.yaml):
                      birotor-estimator --vehicle and birotor-sim --vehicle talk on the counted
                      channels (STRAIN_N, MOTOR_N, FORCE_N, TRUTH_N); the run is recorded
                      (lcm-logger) and its figures printed per rotor from the recording
                      (birotor-eval --vehicle FILE --log, the same table as in-process),
                      with the review page; no live view (birotor-monitor reads the birotor's
                      channels). With --controller MODE: birotor-controller --vehicle flies the
                      simulator's ESCs on MOTOR_COMMAND_N (sealed) from FORCE_N and the
                      scenario's trajectory on SETPOINT (birotor-sim --publish-setpoints)
  --no-setup          skip tools/setup.sh (no install, no build); use the existing build
  -h, --help          this help

Environment: BIROTOR_BUILD_DIR (default: build), BIROTOR_JOBS (build jobs), as tools/setup.sh.
Logs: <out>/demo-<scenario>-{setup,estimator,controller,sim,monitor,logger}.log; with --controller
or --vehicle also <out>/demo-<scenario>-flight.lcm and -review.html.
Exit status: 0 when every step succeeded, 1 when one failed, 2 on wrong usage.
EOF
}

die_usage() { echo "demo.sh: error: $1 (see --help)" >&2; exit 2; }
fail() { echo "demo.sh: error: $1" >&2; exit 1; }

scenario="gentle"
speed="1"
method=""
lcm_url="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"
out_dir="out"
run_setup=1
no_truth=0
controller_mode=""
vehicle_file=""
scenario_given=0
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --speed) [ $# -ge 2 ] || die_usage "--speed needs a value"; speed="$2"; shift 2 ;;
    --speed=*) speed="${1#*=}"; shift ;;
    --method) [ $# -ge 2 ] || die_usage "--method needs a value"; method="$2"; shift 2 ;;
    --method=*) method="${1#*=}"; shift ;;
    --lcm-url) [ $# -ge 2 ] || die_usage "--lcm-url needs a value"; lcm_url="$2"; shift 2 ;;
    --lcm-url=*) lcm_url="${1#*=}"; shift ;;
    --out) [ $# -ge 2 ] || die_usage "--out needs a value"; out_dir="$2"; shift 2 ;;
    --out=*) out_dir="${1#*=}"; shift ;;
    --controller) [ $# -ge 2 ] || die_usage "--controller needs a value"; controller_mode="$2"; shift 2 ;;
    --controller=*) controller_mode="${1#*=}"; shift ;;
    --vehicle) [ $# -ge 2 ] || die_usage "--vehicle needs a value"; vehicle_file="$2"; shift 2 ;;
    --vehicle=*) vehicle_file="${1#*=}"; shift ;;
    --no-setup) run_setup=0; shift ;;
    --no-truth) no_truth=1; shift ;;
    -*) die_usage "unknown option $1" ;;
    *) [ "$scenario_given" -eq 0 ] || die_usage "more than one scenario given ($scenario, $1)"
       scenario="$1"; scenario_given=1; shift ;;
  esac
done

# Arguments are checked before anything is installed or built.
case "$scenario" in
  *.yaml|*/*) scenario_file="$scenario"; scenario="$(basename "$scenario" .yaml)" ;;
  *) scenario_file="config/scenarios/$scenario.yaml" ;;
esac
if [ ! -f "$scenario_file" ]; then
  names="$(cd config/scenarios && ls ./*.yaml | sed 's|^\./||; s|\.yaml$||' | tr '\n' ' ')"
  die_usage "no scenario '$scenario' ($scenario_file not found); available: $names"
fi
[[ "$speed" =~ ^[0-9]*\.?[0-9]+$ ]] && awk "BEGIN{exit !($speed > 0)}" \
  || die_usage "--speed must be a positive number, got '$speed'"
case "$method" in ""|ekf|inversion|motor_map) ;; *) die_usage "--method must be ekf, inversion or motor_map, got '$method'" ;; esac
case "$controller_mode" in ""|nominal|force_feedback|mpc) ;; *) die_usage "--controller must be nominal, force_feedback or mpc, got '$controller_mode'" ;; esac
# The controller flies on the wall clock (birotor-sim refuses --external-controller
# at another speed): closed loop faster than real time is birotor-eval --control.
if [ -n "$controller_mode" ] && awk "BEGIN{exit !($speed != 1)}"; then
  die_usage "--controller flies in real time: it needs --speed 1, got '$speed' (faster: build/tools/birotor-eval --control)"
fi
if [ -n "$vehicle_file" ]; then
  [ -f "$vehicle_file" ] || die_usage "no vehicle description $vehicle_file"
  [ "$no_truth" -eq 0 ] || die_usage "--vehicle needs the truth for its figures (no --no-truth)"
  vehicle_file="$(cd "$(dirname "$vehicle_file")" && pwd)/$(basename "$vehicle_file")"
fi
mkdir -p "$out_dir" 2>/dev/null || fail "cannot create the output folder $out_dir"
[ -w "$out_dir" ] || fail "cannot write to the output folder $out_dir"
out_dir="$(cd "$out_dir" && pwd)"
png="$out_dir/demo-$scenario.png"
log_prefix="$out_dir/demo-$scenario"
# The programs authenticate MOTOR_COMMAND, SETPOINT, POSE and FORCE (and the
# N-arm MOTOR_COMMAND_N and FORCE_N) with a
# site key (docs/deploy.md, "The site key"): the demo makes its own, 32
# random bytes only its owner reads, fresh for each run.
site_key="$out_dir/demo-site.key"
rm -f "$site_key"
(umask 077 && head -c 32 /dev/urandom > "$site_key") || fail "cannot write the demo's site key $site_key"

# 1. Install what is missing and build (idempotent; quick when up to date).
build_dir="${BIROTOR_BUILD_DIR:-build}"
if [ "$run_setup" -eq 1 ]; then
  echo "demo: installing missing packages and building into $build_dir (tools/setup.sh, log: $log_prefix-setup.log) ..."
  if ! tools/setup.sh > "$log_prefix-setup.log" 2>&1; then
    tail -n 30 "$log_prefix-setup.log" >&2
    fail "tools/setup.sh failed; full log: $log_prefix-setup.log"
  fi
fi
find_program() {
  local path
  path="$(find "$build_dir" -name "$1" -type f -perm -u+x 2>/dev/null | head -n 1)"
  [ -n "$path" ] || fail "$1 not found under $build_dir; build first (tools/setup.sh) or drop --no-setup"
  echo "$path"
}
sim_bin="$(find_program birotor-sim)"
estimator_bin="$(find_program birotor-estimator)"
monitor_bin="$(find_program birotor-monitor)"
if [ -n "$controller_mode" ] || [ -n "$vehicle_file" ]; then
  [ -z "$controller_mode" ] || controller_bin="$(find_program birotor-controller)"
  review_bin="$(find_program birotor-review)"
  command -v lcm-logger > /dev/null || fail "lcm-logger not found (apt-get install liblcm-bin; tools/setup.sh)"
fi

# 2. Processes: started here, stopped here by PID (SIGTERM, wait, SIGKILL after 5 s).
estimator_pid=""
controller_pid=""
logger_pid=""
sim_pid=""
monitor_pid=""
stop_process() {  # name pid
  local pid="$2"
  [ -n "$pid" ] || return 0
  kill -0 "$pid" 2>/dev/null || { wait "$pid" 2>/dev/null || true; return 0; }
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2>/dev/null; then
    echo "demo: $1 (pid $pid) did not stop on SIGTERM; killing it" >&2
    kill -KILL "$pid" 2>/dev/null || true
  fi
  wait "$pid" 2>/dev/null || true
}
cleanup() {
  stop_process birotor-sim "$sim_pid"; sim_pid=""
  stop_process birotor-monitor "$monitor_pid"; monitor_pid=""
  stop_process birotor-estimator "$estimator_pid"; estimator_pid=""
  stop_process birotor-controller "$controller_pid"; controller_pid=""
  stop_process lcm-logger "$logger_pid"; logger_pid=""
}
trap cleanup EXIT
trap 'echo "demo: interrupted; stopping" >&2; cleanup; exit 130' INT TERM

# Waits until a process's log contains a pattern; fails if it exits first.
wait_for_log() {  # name pid logfile pattern timeout_s
  local deadline=$((SECONDS + $5))
  until grep -q "$4" "$3" 2>/dev/null; do
    if ! kill -0 "$2" 2>/dev/null; then
      tail -n 5 "$3" >&2
      fail "$1 stopped during start-up (log: $3)"
    fi
    [ $SECONDS -lt "$deadline" ] || fail "$1 did not start within $5 s (log: $3)"
    sleep 0.1
  done
}

rmem_max="$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 0)"
if [[ "$lcm_url" == *recv_buf_size=* ]] && [ "$rmem_max" -lt 2097152 ]; then
  echo "demo: note: the kernel caps UDP receive buffers at $rmem_max B; if packets are lost," \
       "raise it: sudo sysctl -w net.core.rmem_max=2097152"
fi
duration_s="$(awk '/^[[:space:]]*duration_s:/ {print $2; exit}' "$scenario_file")"
echo "demo: scenario $scenario (${duration_s:-?} s at speed $speed), LCM $lcm_url"
[ -z "$vehicle_file" ] || { source tools/demo_vehicle.sh; run_vehicle_demo; exit $?; }
# SCHED_FIFO priorities of the shipped units (docs/realtime.md): the simulator
# (the vehicle) above the controller above the estimator, so a busy machine
# does not delay a sample or a command. Without CAP_SYS_NICE each program warns
# once in its log and runs on the normal scheduler.
estimator_args=(--lcm-url "$lcm_url" --params "$repo/config/estimator.yaml" --realtime-priority 50 --site-key "$site_key")
[ -n "$method" ] && estimator_args+=(--method "$method")
"$estimator_bin" "${estimator_args[@]}" > "$log_prefix-estimator.log" 2>&1 &
estimator_pid=$!
wait_for_log birotor-estimator "$estimator_pid" "$log_prefix-estimator.log" "lcm .*: in " 20

# The monitor's stdout is this terminal (live view) or the CI log (plain lines).
monitor_args=(--lcm-url "$lcm_url" --scenario "$scenario_file" --label "$scenario" --until-sim-ends
  --idle-s 1.5 --startup-timeout-s 30 --png "$png" --markdown)
sim_args=(--scenario "$scenario_file" --lcm-url "$lcm_url" --speed "$speed" --realtime-priority 60 --site-key "$site_key")
if [ "$no_truth" -eq 1 ]; then
  monitor_args+=(--no-truth)
  sim_args+=(--no-truth)
fi
if [ -n "$controller_mode" ]; then
  "$controller_bin" --lcm-url "$lcm_url" --params "$repo/config/controller.yaml" --mode "$controller_mode" \
    --realtime-priority 55 --site-key "$site_key" > "$log_prefix-controller.log" 2>&1 &
  controller_pid=$!
  wait_for_log birotor-controller "$controller_pid" "$log_prefix-controller.log" "lcm .*: in " 20
  sim_args+=(--external-controller)
  echo "demo: closed loop: birotor-controller ($controller_mode) flies the simulator on MOTOR_COMMAND"
  # The flight is recorded for its figures and review page (birotor-review).
  flight_log="$log_prefix-flight.lcm"
  lcm-logger --lcm-url "$lcm_url" --channel "BIROTOR_.*" --force "$flight_log" > "$log_prefix-logger.log" 2>&1 &
  logger_pid=$!
fi
"$monitor_bin" "${monitor_args[@]}" 2> "$log_prefix-monitor.log" &
monitor_pid=$!
wait_for_log birotor-monitor "$monitor_pid" "$log_prefix-monitor.log" "listening on" 20

"$sim_bin" "${sim_args[@]}" > "$log_prefix-sim.log" 2>&1 &
sim_pid=$!

status=0
wait "$sim_pid" || { echo "demo: birotor-sim failed (log: $log_prefix-sim.log)" >&2; tail -n 5 "$log_prefix-sim.log" >&2; status=1; }
sim_pid=""
wait "$monitor_pid" || { echo "demo: birotor-monitor failed (log: $log_prefix-monitor.log)" >&2; tail -n 5 "$log_prefix-monitor.log" >&2; status=1; }
monitor_pid=""
if ! kill -0 "$estimator_pid" 2>/dev/null; then
  echo "demo: birotor-estimator stopped before the end (log: $log_prefix-estimator.log)" >&2
  status=1
fi
stop_process birotor-estimator "$estimator_pid"
estimator_pid=""
grep -h "stopped:" "$log_prefix-estimator.log" | sed 's/^.*\] /estimator: /' || true
if [ -n "$controller_mode" ]; then
  kill -0 "$controller_pid" 2>/dev/null || { echo "demo: birotor-controller stopped before the end (log: $log_prefix-controller.log)" >&2; status=1; }
  stop_process birotor-controller "$controller_pid"
  controller_pid=""
  grep -h "stopped:" "$log_prefix-controller.log" | sed 's/^.*\] /controller: /' || true
  stop_process lcm-logger "$logger_pid"
  logger_pid=""
  # Flight figures (position held, commands, fallbacks with their times) and the review page.
  if "$review_bin" "$flight_log" --output "$log_prefix-review.html" --log-level warn > "$log_prefix-review.txt"; then
    grep "^flight: " "$log_prefix-review.txt" | sed 's/^flight: /flight: /'
    echo "demo: review page: $log_prefix-review.html (recorded flight: $flight_log)"
    # The one verdict (samples/flight_verdict.h): a lost vehicle fails the demo.
    if grep -q "^flight: verdict: LOST" "$log_prefix-review.txt"; then
      echo "demo: the vehicle was LOST: $(sed -n 's/^flight: verdict: //p' "$log_prefix-review.txt" | head -n 1)" >&2
      status=1
    fi
  else
    echo "demo: birotor-review failed on $flight_log" >&2
    status=1
  fi
  echo "demo: the same flight in-process (lock-step, figures of both modes): birotor-eval --control --scenarios $scenario"
fi
grep -h "simulated " "$log_prefix-sim.log" | sed 's/^.*\] /simulator: /' || true
# Identical figures to birotor-eval need every strain packet delivered and fused in order.
sent="$(sed -n 's/.*samples: strain \([0-9]*\),.*/\1/p' "$log_prefix-sim.log" | tail -n 1)"
received="$(sed -n 's/.*strain received \([0-9]*\) .*/\1/p' "$log_prefix-estimator.log" | tail -n 1)"
if [ -n "$sent" ] && [ -n "$received" ] && [ "$received" -lt "$sent" ]; then
  echo "demo: note: $((sent - received)) of $sent strain packets were lost between simulator and estimator" \
       "(UDP receive buffer overflow on a busy machine), so the figures differ from birotor-eval's" >&2
fi
if grep -q "overload drops [1-9]" "$log_prefix-estimator.log"; then
  echo "demo: note: the estimator shed samples under load, so the figures differ from birotor-eval's" >&2
fi
[ -f "$png" ] || { echo "demo: no plot was written ($png)" >&2; status=1; }
if [ "$status" -eq 0 ]; then
  echo "demo: done. Plot: $png"
  eval_bin="$(find "$build_dir" -name birotor-eval -type f -perm -u+x 2>/dev/null | head -n 1)"
  # birotor-eval takes scenario names, looked up in --scenario-dir when the
  # scenario was given as a file outside config/scenarios/.
  eval_scenario="--scenarios $scenario"
  [ "$scenario_file" = "config/scenarios/$scenario.yaml" ] || eval_scenario="--scenario-dir $(dirname "$scenario_file") $eval_scenario"
  [ -z "$eval_bin" ] || [ "$no_truth" -eq 1 ] || echo "demo: same figures in-process: ${eval_bin#"$repo/"} $eval_scenario --methods ${method:-$(awk '/^[[:space:]]*method:/ {print $2; exit}' config/estimator.yaml)}"
fi
exit "$status"
