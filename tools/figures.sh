#!/usr/bin/env bash
# Regenerates docs/figures.md: every measured figure the README quotes, from
# the project's own programs on the built tree (birotor-analyze, birotor-eval,
# birotor-sim + birotor-identify, birotor-replay, the benchmarks, a live
# latency run), headed by the commit and the machine it ran on.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"

usage() {
  cat <<'EOF'
Usage: tools/figures.sh [--quick] [--output FILE] [--no-latency] [--no-readme]

Runs the project's tools on the built tree (build/, or $BIROTOR_BUILD_DIR) and
writes the figures with the commands that produced them to docs/figures.md
(written to a temporary file, renamed on success). Build first: tools/setup.sh.

  --quick         shorter runs (a few scenarios, 30 s bench log, no flight
                  identification, one benchmark repetition): about a minute;
                  the header says the figures are quick ones
  --output FILE   where to write (default: docs/figures.md)
  --no-latency    skip the live latency run (it needs udpm on loopback)
  --no-readme     leave README.md alone (a full run rewrites its headline
                  block, between <!-- figures:begin --> and <!-- figures:end -->,
                  and its example plot docs/thrust_loss_ekf.png)
  -h, --help      this help

Each section says how much its figures move between runs: the accuracy,
control and identification figures are deterministic (fixed seeds) and
change only with the code; times depend on the machine and its load, which
the header records.
Exit status: 0 on success, 1 when a step failed, 2 on wrong usage.
EOF
}

quick=0; latency=1; readme=1; output="docs/figures.md"
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --quick) quick=1; shift ;;
    --no-latency) latency=0; shift ;;
    --no-readme) readme=0; shift ;;
    --output) [ $# -ge 2 ] || { echo "figures.sh: error: --output needs a value" >&2; exit 2; }; output="$2"; shift 2 ;;
    --output=*) output="${1#*=}"; shift ;;
    *) echo "figures.sh: error: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done

build="${BIROTOR_BUILD_DIR:-build}"
fail() { echo "figures.sh: error: $1" >&2; exit 1; }
for program in services/birotor-sim services/birotor-estimator tools/birotor-analyze tools/birotor-eval \
               tools/birotor-identify tools/birotor-replay tools/birotor-latency-probe \
               benchmarks/estimator_benchmark; do
  [ -x "$build/$program" ] || fail "$build/$program not built (run tools/setup.sh)"
done
sim="$build/services/birotor-sim"; estimator="$build/services/birotor-estimator"

work="$(mktemp -d)"; estimator_pid=""
cleanup() {
  if [ -n "$estimator_pid" ] && kill -0 "$estimator_pid" 2>/dev/null; then
    kill -TERM "$estimator_pid" 2>/dev/null || true
    wait "$estimator_pid" 2>/dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT
out="$work/figures.md"

# Timing, the run/timed wrappers and the table readers (cell, identification_table, ...).
source "$repo/tools/figures_lib.sh"

script_start="$(now_s)"
start_load="$(load)"
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD 2>/dev/null || commit="$commit (with uncommitted changes)"
cpu="$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)"
memory="$(awk '/^MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo)"
os="$(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME" || uname -sr)"
compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt" | head -n 1)"
compiler="$("${compiler:-c++}" --version 2>/dev/null | head -n 1 || echo unknown)"
build_type="$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build/CMakeCache.txt" | head -n 1)"
mode="full"
[ "$quick" -eq 0 ] || mode="quick (tools/figures.sh --quick: shorter runs, not the reference figures)"

# --- Model ---------------------------------------------------------------
step "model (birotor-analyze)"
run analyze "$build/tools/birotor-analyze"

# --- Estimator accuracy --------------------------------------------------
if [ "$quick" -eq 1 ]; then
  eval_args=(--scenarios hover,thrust_loss --methods ekf,linear_kf,inversion,motor_map)
else
  eval_args=()
fi
step "estimator accuracy (birotor-eval ${eval_args[*]})"
eval_s="$(timed eval "$build/tools/birotor-eval" "${eval_args[@]}")"

# The example force plot of the README (full runs only).
if [ "$quick" -eq 0 ]; then
  step "example plot (birotor-eval --scenarios thrust_loss --methods ekf --plot-dir ...)"
  run plot "$build/tools/birotor-eval" --scenarios thrust_loss --methods ekf --plot-dir "$work/plots"
fi

# --- Closed-loop control -------------------------------------------------
if [ "$quick" -eq 1 ]; then control_args=(--control --scenarios thrust_loss); else control_args=(--control); fi
step "closed-loop control (birotor-eval ${control_args[*]})"
control_s="$(timed control "$build/tools/birotor-eval" "${control_args[@]}")"

# --- The three-rotor vehicle ---------------------------------------------
trirotor="$repo/config/vehicles/trirotor.yaml"
if [ "$quick" -eq 1 ]; then
  tri_eval_args=(--scenarios hover,thrust_loss); tri_control_args=(--control --scenarios lateral_step,loss40_rotor1)
else
  tri_eval_args=(--scenarios hover,gentle,aggressive,thrust_loss); tri_control_args=(--control)
fi
step "three-rotor vehicle: accuracy and control (birotor-eval --vehicle config/vehicles/trirotor.yaml)"
tri_eval_s="$(timed tri_eval "$build/tools/birotor-eval" --vehicle "$trirotor" "${tri_eval_args[@]}")"
tri_control_s="$(timed tri_control "$build/tools/birotor-eval" --vehicle "$trirotor" "${tri_control_args[@]}")"
# The same lateral step on the birotor description: it must tilt to move.
run bi_lateral "$build/tools/birotor-eval" --vehicle "$repo/config/vehicles/birotor.yaml" --control --scenarios lateral_step

# --- Identification ------------------------------------------------------
# Vehicle B: every identified parameter differs from the reference file the
# fit starts from.
# Vehicle B's true values, key=value (the --set lines of vehicle_b).
truth_b="thrust_coeff_n_s2_rad2=5.0e-5 motor_time_constant_s=0.042 arm_stiffness_n_m_rad=3100
arm_damping_n_m_s_rad=0.30 tip_mass_kg=0.31"
vehicle_b=(--set vehicle.arm_stiffness_n_m_rad=3100 --set vehicle.arm_damping_n_m_s_rad=0.30
  --set vehicle.tip_mass_kg=0.31 --set vehicle.thrust_coeff_n_s2_rad2=5.0e-5 --set vehicle.motor_time_constant_s=0.042)
bench_s=120
[ "$quick" -eq 0 ] || bench_s=30
step "identification: ${bench_s} s bench log of vehicle B"
run bench_sim "$sim" --scenario bench --set scenario.duration_s=$bench_s "${vehicle_b[@]}" --output "$work/bench.lcm"
bench_id_s="$(timed bench_id /usr/bin/time -f '%U %S' -o "$work/bench_id.cpu" "$build/tools/birotor-identify" \
  --log "$work/bench.lcm" --output "$work/bench_vehicle.yaml" --report "$work/bench_report.md")"
if [ "$quick" -eq 0 ]; then
  step "identification: 60 s flight log of vehicle B on the bench result"
  run flight_sim "$sim" --scenario flight_id "${vehicle_b[@]}" --output "$work/flight.lcm"
  cp "$repo/config/estimator.yaml" "$work/bench_base.yaml"
  run bench_update "$build/tools/birotor-identify" --log "$work/bench.lcm" --update-params "$work/bench_base.yaml"
  # The chain: the EKF on B's gentle flight with the identified file against
  # the same file holding B's true values.
  sed -e 's/^\(  arm_stiffness_n_m_rad:\) *[0-9.e+-]*/\1 3100/' -e 's/^\(  arm_damping_n_m_s_rad:\) *[0-9.e+-]*/\1 0.30/' \
      -e 's/^\(  tip_mass_kg:\) *[0-9.e+-]*/\1 0.31/' -e 's/^\(  thrust_coeff_n_s2_rad2:\) *[0-9.e+-]*/\1 5.0e-5/' \
      -e 's/^\(  motor_time_constant_s:\) *[0-9.e+-]*/\1 0.042/' "$repo/config/estimator.yaml" > "$work/true_b.yaml"
  step "identification chain: EKF on vehicle B's gentle flight, true and identified parameters"
  run chain_true "$build/tools/birotor-eval" --scenarios gentle --methods ekf "${vehicle_b[@]}" --params "$work/true_b.yaml"
  run chain_identified "$build/tools/birotor-eval" --scenarios gentle --methods ekf "${vehicle_b[@]}" \
    --params "$work/bench_base.yaml"
  flight_id_s="$(timed flight_id /usr/bin/time -f '%U %S' -o "$work/flight_id.cpu" "$build/tools/birotor-identify" \
    --mode flight --params "$work/bench_base.yaml" --log "$work/flight.lcm" --output "$work/flight_vehicle.yaml" \
    --report "$work/flight_report.md")"
fi

# --- Speed ---------------------------------------------------------------
step "speed: simulator, replay"
sim60_s="$(timed sim60 "$sim" --scenario gentle --set scenario.duration_s=60 --output "$work/g60.lcm")"
run gentle_sim "$sim" --scenario gentle --output "$work/gentle.lcm"
replay_runs=3
[ "$quick" -eq 0 ] || replay_runs=1
replay_times=()
for _ in $(seq "$replay_runs"); do
  replay_times+=("$(timed replay "$build/tools/birotor-replay" --log "$work/gentle.lcm" --output "$work/est.lcm")")
done
replay_s="$(printf '%s\n' "${replay_times[@]}" | sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')"
reps=5
[ "$quick" -eq 0 ] || reps=1
step "speed: estimator benchmark (repetitions $reps)"
run bench_est "$build/benchmarks/estimator_benchmark" \
  --benchmark_filter='BM_StrainSample|BM_HarmonicNotchSample|BM_PipelineGentle10s' \
  --benchmark_repetitions=$reps --benchmark_report_aggregates_only=$([ $reps -gt 1 ] && echo true || echo false)

# --- Latency -------------------------------------------------------------
if [ "$latency" -eq 1 ]; then
  step "latency: estimator + probe over udpm loopback, 10 s at 1 kHz"
  port=$((20000 + $$ % 20000))
  url="udpm://239.255.76.67:$port?ttl=0&recv_buf_size=4194304"
  # FORCE goes out sealed (FORCE_AUTH) under this run's own site key.
  (umask 077 && head -c 32 /dev/urandom > "$work/site.key")
  "$estimator" --lcm-url "$url" --prefix FIGURES_ --site-key "$work/site.key" > "$work/latency_estimator.log" 2>&1 &
  estimator_pid=$!
  for _ in $(seq 100); do grep -q "lcm .*: in " "$work/latency_estimator.log" 2>/dev/null && break; sleep 0.1; done
  # Exit status 3: measured, but some samples got no FORCE (the output says how many).
  latency_status=0
  "$build/tools/birotor-latency-probe" --lcm-url "$url" --prefix FIGURES_ --rate-hz 1000 --duration-s 10 \
    > "$work/latency.out" 2> "$work/latency.err" || latency_status=$?
  [ "$latency_status" -eq 0 ] || [ "$latency_status" -eq 3 ] || { cat "$work/latency.err" >&2; fail "latency probe failed"; }
  kill -TERM "$estimator_pid"
  wait "$estimator_pid" || true
  estimator_pid=""
fi

# --- Tests ---------------------------------------------------------------
# GoogleTest cases are registered when their program is built: a partial
# build gives a partial count, and the figure says so.
tests="$(ctest --test-dir "$build" -N 2>/dev/null | sed -n 's/^Total Tests: //p')"
missing_test_programs=0
for test_program in $(grep -rhoE 'birotor_add_test\(NAME [A-Za-z0-9_]+' tests | sed 's/.*NAME //' | sort -u); do
  [ -n "$(find "$build/tests" -name "$test_program" -type f -perm -u+x 2>/dev/null)" ] || missing_test_programs=$((missing_test_programs + 1))
done
if [ "$missing_test_programs" -gt 0 ]; then
  tests="$tests (partial: $missing_test_programs test programs not built; their cases are not counted)"
fi

end_load="$(load)"
total_s="$(elapsed "$script_start")"
step "writing $output (${total_s} s)"
identification_table "$work/bench_report.md" > "$work/bench_table.md"
[ "$quick" -eq 1 ] || identification_table "$work/flight_report.md" > "$work/flight_table.md"
date_utc="$(date -u '+%Y-%m-%d %H:%M UTC')"
machine="$(nproc) cores ($cpu), load average $start_load"

# --- The headline: the block the README quotes ---------------------------
ekf_false_alarms="$(awk -F' *\\| *' '/^\| scenario/ { for (i = 2; i < NF; ++i) if ($i == "false alarms") c = i; next }
  c && $3 == "ekf" { sum += $c } END { print sum + 0 }' "$work/eval.out")"
{
  cat <<EOF
From [docs/figures.md](docs/figures.md), written by \`tools/figures.sh\`$([ "$quick" -eq 0 ] || echo " --quick") on
$date_utc (commit $commit; $machine). Accuracy, control and identification use fixed seeds: the same commit
gives the same numbers. Times depend on the machine and its load.

**Force accuracy** (\`birotor-eval\`, reference noise, MAE of rotor 1 / rotor 2 in newtons, first 0.5 s not
scored; "within 2 sigma": share of EKF errors inside twice its own reported sigma, 0.95 expected):

| scenario | EKF | within 2 sigma | inversion (thesis) | motor map |
|---|---|---|---|---|
EOF
  for scenario in hover gentle aggressive thrust_loss density sensor_faults; do
    grep -q "^| $scenario | ekf |" "$work/eval.out" || continue
    printf '| %s | %s / %s | %s | %s / %s | %s / %s |\n' "$scenario" \
      "$(cell "$work/eval.out" "$scenario" ekf 'MAE f1 [N]')" "$(cell "$work/eval.out" "$scenario" ekf 'MAE f2 [N]')" \
      "$(cell "$work/eval.out" "$scenario" ekf 'within 2 sigma f1 / f2')" \
      "$(cell "$work/eval.out" "$scenario" inversion 'MAE f1 [N]')" "$(cell "$work/eval.out" "$scenario" inversion 'MAE f2 [N]')" \
      "$(cell "$work/eval.out" "$scenario" motor_map 'MAE f1 [N]')" "$(cell "$work/eval.out" "$scenario" motor_map 'MAE f2 [N]')"
  done
  cat <<EOF

In \`thrust_loss\` (rotor 2 loses a quarter of its thrust at 5 s) the EKF flags rotor 2 **$(cell "$work/eval.out" thrust_loss ekf 'fault delay [ms]') ms**
after the step and its thrust_scale is off by **$(cell "$work/eval.out" thrust_loss ekf 'scale err +100 ms')** 100 ms after it; false
fault alarms of the EKF over every scenario: **$ekf_false_alarms**.

**Closed-loop control** (\`birotor-eval --control\`, \`thrust_loss\`, the same gains in both modes):

| controller | RMS position error [m] | peak tilt after the fault [rad] | altitude deviation after the fault [m] | back within 5 cm [s] |
|---|---|---|---|---|
EOF
  for controller in nominal force_feedback; do
    printf '| %s | %s | %s | %s | %s |\n' "$controller" \
      "$(cell "$work/control.out" thrust_loss "$controller" 'RMS position error [m]')" \
      "$(cell "$work/control.out" thrust_loss "$controller" 'tilt after event [rad]')" \
      "$(cell "$work/control.out" thrust_loss "$controller" 'altitude deviation [m]')" \
      "$(cell "$work/control.out" thrust_loss "$controller" 'back within 5 cm [s]')"
  done
  cat <<EOF

**Three-rotor vehicle** (\`birotor-eval --vehicle config/vehicles/trirotor.yaml\`, the same estimator file): EKF MAE
per rotor in hover $(cell "$work/tri_eval.out" hover "" 'MAE per rotor [N]') N, within 2 sigma $(cell "$work/tri_eval.out" hover "" '2-sigma share per rotor');
in \`thrust_loss\` rotor $(cell "$work/tri_eval.out" thrust_loss "" 'step rotor') is flagged after $(cell "$work/tri_eval.out" thrust_loss "" 'detection [ms]') ms.
A 1 m lateral step at a peak tilt of $(control_cell "$work/tri_control.out" lateral_step 'fully actuated' nominal 'max tilt [rad]') rad (the birotor tilts
$(control_cell "$work/bi_lateral.out" lateral_step 'tilt to move' nominal 'max tilt [rad]') rad for it); after a 40 % loss on rotor 1 the cascade loses
$(control_cell "$work/tri_control.out" loss40_rotor1 'fully actuated' nominal 'altitude dev. after loss [m]') m of altitude on the nominal map and $(control_cell "$work/tri_control.out" loss40_rotor1 'fully actuated' 'estimated (N-arm EKF)' 'altitude dev. after loss [m]') m on the estimated efficiencies.

**Identification** of a vehicle whose every parameter differs from the file the fit starts from
(error, and error in units of the reported one sigma), ${bench_s} s bench log, ${bench_id_s} s wall:
c_T $(id_error "$work/bench_table.md" thrust_coeff_n_s2_rad2), tau_m $(id_error "$work/bench_table.md" motor_time_constant_s),
k $(id_error "$work/bench_table.md" arm_stiffness_n_m_rad), m_p $(id_error "$work/bench_table.md" tip_mass_kg),
d $(id_error "$work/bench_table.md" arm_damping_n_m_s_rad).
EOF
  if [ "$quick" -eq 0 ]; then
    cat <<EOF
From a 60 s flight on top of the bench result (${flight_id_s} s wall): c_T $(id_error "$work/flight_table.md" thrust_coeff_n_s2_rad2),
tau_m $(id_error "$work/flight_table.md" motor_time_constant_s), k $(id_error "$work/flight_table.md" arm_stiffness_n_m_rad),
m_p $(flight_mp="$(id_error "$work/flight_table.md" tip_mass_kg)"; [ "$flight_mp" != "?" ] && echo "$flight_mp" || echo "kept at the bench value (the flight fit writes it only when it disagrees by more than 5 sigma)").
EOF
  fi
  cat <<EOF

**Speed** on this machine: one strain sample through the EKF (with the MOTOR and IMU samples before it)
$(benchmark_time BM_StrainSample/ekf) (median of $reps); the whole pipeline over 10 s of \`gentle\` $(benchmark_time BM_PipelineGentle10s/shipped);
\`birotor-replay\` of a 15 s log in ${replay_s} s ($(awk -v t="$replay_s" 'BEGIN { printf "%.0f", 15 / t }')x real time);
60 s simulated into a log in ${sim60_s} s.
EOF
  if [ "$latency" -eq 1 ]; then
    echo "Latency STRAIN published to FORCE received, udpm loopback, 1 kHz for 10 s [us]:"
    echo "$(sed -n 's/^latency publish->FORCE \[us\]: //p' "$work/latency.out" | tr -s ' ')."
  fi
  echo
  echo "**Tests**: $tests in CTest."
} > "$work/headline.md"

# --- The document --------------------------------------------------------
{
  cat <<EOF
# Measured figures

Generated by \`tools/figures.sh\`; do not edit by hand. Every figure the
README quotes comes from here. Run it again after a change and commit the
result.

| | |
|---|---|
| date | $(date -u '+%Y-%m-%d %H:%M UTC') |
| commit | $commit |
| mode | $mode |
| machine | $(nproc) cores, $cpu, $memory, $os |
| build | $compiler, CMAKE_BUILD_TYPE=$build_type |
| load average (1, 5, 15 min) | $start_load at the start, $end_load at the end |
| runtime of the script | $total_s s |

Times below were taken on this machine under this load; on a shared or busy
machine they are slower by up to the load average divided by the core count.
The accuracy, control and identification figures use fixed seeds: they are
identical on every run of the same commit.

## Headline (quoted in the README)

EOF
  cat "$work/headline.md"
  cat <<EOF

## Model

\`$build/tools/birotor-analyze\` (reference vehicle; asserted in \`tests/model/\`):

\`\`\`
EOF
  sed -n '/^Hover equilibrium/,/^$/p; /^Arm modes/,/^$/p' "$work/analyze.out"
  echo '```'
  echo
  sed -n '/^| measured/,/^$/p' "$work/analyze.out"
  grep '^Controllability' "$work/analyze.out"
  cat <<EOF

## Estimator accuracy

\`$build/tools/birotor-eval ${eval_args[*]}\` (${eval_s} s wall): every method on
every scenario at the reference noise, first 0.5 s not scored. Deterministic.

EOF
  cat "$work/eval.out"
  cat <<EOF

## Closed-loop control

\`$build/tools/birotor-eval ${control_args[*]}\` (${control_s} s wall): simulator,
estimator pipeline and controller in lock-step on the simulated clock, both
controller modes with the same gains. Deterministic.

EOF
  cat "$work/control.out"
  cat <<EOF

## Three-rotor vehicle

\`$build/tools/birotor-eval --vehicle config/vehicles/trirotor.yaml ${tri_eval_args[*]}\` (${tri_eval_s} s wall):
the EKF for N arms on the thesis's three-rotor vehicle, with the scenario files' sensors and gauges, fixed seeds. Deterministic.

EOF
  cat "$work/tri_eval.out"
  cat <<EOF

\`$build/tools/birotor-eval --vehicle config/vehicles/trirotor.yaml ${tri_control_args[*]}\` (${tri_control_s} s wall):
the N-rotor controller in lock-step, cascade and mode mpc, nominal map and estimated efficiencies (the MPC
solve times are CPU times on this machine; everything else is deterministic). First the birotor description
on the same lateral step (\`--vehicle config/vehicles/birotor.yaml --control --scenarios lateral_step\`):

EOF
  sed -n '/^| case/,$p' "$work/bi_lateral.out"
  echo
  sed -n '/^| case/,$p' "$work/tri_control.out"
  cat <<EOF

## Identification

Vehicle B (\`birotor-sim ${vehicle_b[*]}\`: k 3100, d 0.30, m_p 0.31,
c_T 5.0e-5, tau_m 0.042), identified from the reference file (k 2628, d 0.25,
m_p 0.28812, c_T 4.6e-5, tau_m 0.035). Deterministic (fixed seeds).

Bench: \`birotor-sim --scenario bench --set scenario.duration_s=$bench_s ...
--output bench.lcm\`, then \`birotor-identify --log bench.lcm --output
vehicle.yaml --report report.md\`: ${bench_id_s} s wall, $(awk '{ printf "%.1f", $1 + $2 }' "$work/bench_id.cpu") s CPU.

EOF
  cat "$work/bench_table.md"
  if [ "$quick" -eq 0 ]; then
    cat <<EOF

Flight: \`birotor-sim --scenario flight_id ... --output flight.lcm\` (60 s), then
\`birotor-identify --mode flight --params <the bench-identified file> --log
flight.lcm\`: ${flight_id_s} s wall, $(awk '{ printf "%.1f", $1 + $2 }' "$work/flight_id.cpu") s CPU.

EOF
    cat "$work/flight_table.md"
    cat <<EOF

The chain: \`birotor-eval --scenarios gentle --methods ekf <vehicle B> --params FILE\`
with B's true values in the estimator's file, and with the bench-identified
file (\`birotor-identify --update-params\` on a copy of \`config/estimator.yaml\`):

| parameters | MAE f1 [N] | MAE f2 [N] | within 2 sigma f1 / f2 |
|---|---|---|---|
| true | $(cell "$work/chain_true.out" gentle ekf 'MAE f1 [N]') | $(cell "$work/chain_true.out" gentle ekf 'MAE f2 [N]') | $(cell "$work/chain_true.out" gentle ekf 'within 2 sigma f1 / f2') |
| identified (bench) | $(cell "$work/chain_identified.out" gentle ekf 'MAE f1 [N]') | $(cell "$work/chain_identified.out" gentle ekf 'MAE f2 [N]') | $(cell "$work/chain_identified.out" gentle ekf 'within 2 sigma f1 / f2') |
EOF
  fi
  cat <<EOF

## Speed

| what | command | wall time |
|---|---|---|
| 60 s of \`gentle\` simulated into a log | \`birotor-sim --scenario gentle --set scenario.duration_s=60 --output g60.lcm\` | ${sim60_s} s |
| 15 s \`gentle\` log ($(du -m "$work/gentle.lcm" | cut -f1) MB) through the estimator, median of $replay_runs | \`birotor-replay --log gentle.lcm --output est.lcm\` | ${replay_s} s ($(awk -v t="$replay_s" 'BEGIN { printf "%.0f", 15 / t }')x real time) |

\`$build/benchmarks/estimator_benchmark --benchmark_filter='BM_StrainSample|BM_HarmonicNotchSample|BM_PipelineGentle10s' --benchmark_repetitions=$reps\`
(one strain sample through each method, with the MOTOR and IMU samples before
it; the notches; the whole pipeline over 10 s of \`gentle\`):

| benchmark | time | CPU |
|---|---|---|
EOF
  awk -v reps="$reps" '
    /^BM_/ {
      name = $1
      if (reps > 1 && name !~ /_median$/) next
      sub(/_median$/, "", name)
      printf "| %s | %s %s | %s %s |\n", name, $2, $3, $4, $5
    }' "$work/bench_est.out"
  if [ "$latency" -eq 1 ]; then
    cat <<EOF

## Latency

\`birotor-estimator --lcm-url '$url' --prefix FIGURES_ &\` then
\`birotor-latency-probe --lcm-url '$url' --prefix FIGURES_ --rate-hz 1000 --duration-s 10\`
(STRAIN published to FORCE received, udpm on loopback, normal scheduling):

\`\`\`
EOF
    cat "$work/latency.out"
    echo '```'
  fi
  cat <<EOF

## Tests

\`ctest --test-dir $build -N\`: **$tests** tests (\`tools/test.sh\` runs them all).
EOF
} > "$out"
mkdir -p "$(dirname "$output")"
cp "$out" "$output.tmp" && mv "$output.tmp" "$output" || fail "could not write $output"
if [ "$quick" -eq 0 ] && [ "$readme" -eq 1 ]; then
  cp "$work/plots/thrust_loss_ekf.png" docs/thrust_loss_ekf.png.tmp && mv docs/thrust_loss_ekf.png.tmp docs/thrust_loss_ekf.png \
    || fail "could not write docs/thrust_loss_ekf.png"
fi
# The README's headline block, between its two markers (full runs only).
if [ "$quick" -eq 0 ] && [ "$readme" -eq 1 ]; then
  grep -q '^<!-- figures:begin' README.md && grep -q '^<!-- figures:end' README.md \
    || fail "README.md has no <!-- figures:begin/end --> markers"
  awk -v block="$work/headline.md" '
    /^<!-- figures:begin/ { print; while ((getline line < block) > 0) print line; skip = 1; next }
    /^<!-- figures:end/ { skip = 0 }
    !skip { print }
  ' README.md > README.md.tmp && mv README.md.tmp README.md || fail "could not update README.md"
  echo "figures: updated the headline block of README.md" >&2
fi
echo "figures: wrote $output in ${total_s} s" >&2
