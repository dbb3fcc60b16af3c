# tools/demo.sh --vehicle FILE: the live run of a vehicle description with N
# arms, sourced by tools/demo.sh after its checks and build (it defines the
# variables and helpers used here: sim_bin, estimator_bin, review_bin,
# lcm_url, speed, scenario, scenario_file, vehicle_file, log_prefix, repo,
# build_dir, site_key, controller_mode, controller_bin, wait_for_log,
# stop_process and the *_pid cleanup). With --controller MODE the loop is
# closed over LCM: birotor-controller --vehicle on FORCE_N, the simulator's
# ESCs on MOTOR_COMMAND_N, the scenario's trajectory on SETPOINT.
run_vehicle_demo() {
  local flight_log="$log_prefix-flight.lcm" status=0 eval_bin
  eval_bin="$(find_program birotor-eval)"
  local sim_args=(--vehicle "$vehicle_file" --scenario "$scenario_file" --lcm-url "$lcm_url" --speed "$speed"
    --realtime-priority 60 --site-key "$site_key")
  echo "demo: vehicle $vehicle_file: birotor-estimator --vehicle and birotor-sim --vehicle on the counted channels"
  "$estimator_bin" --vehicle "$vehicle_file" --lcm-url "$lcm_url" --params "$repo/config/estimator.yaml" \
    --realtime-priority 50 --site-key "$site_key" > "$log_prefix-estimator.log" 2>&1 &
  estimator_pid=$!
  wait_for_log birotor-estimator "$estimator_pid" "$log_prefix-estimator.log" "lcm .*: in " 20
  if [ -n "$controller_mode" ]; then
    "$controller_bin" --vehicle "$vehicle_file" --lcm-url "$lcm_url" --params "$repo/config/controller.yaml" \
      --mode "$controller_mode" --realtime-priority 55 --site-key "$site_key" > "$log_prefix-controller.log" 2>&1 &
    controller_pid=$!
    wait_for_log birotor-controller "$controller_pid" "$log_prefix-controller.log" "lcm .*: in " 20
    sim_args+=(--external-controller --publish-setpoints)
    echo "demo: closed loop: birotor-controller --vehicle ($controller_mode) flies the simulator on MOTOR_COMMAND_N"
  fi
  lcm-logger --lcm-url "$lcm_url" --channel "BIROTOR_.*" --force "$flight_log" > "$log_prefix-logger.log" 2>&1 &
  logger_pid=$!
  sleep 0.5  # the logger subscribes before the first sample
  "$sim_bin" "${sim_args[@]}" > "$log_prefix-sim.log" 2>&1 &
  sim_pid=$!
  wait "$sim_pid" || { echo "demo: birotor-sim failed (log: $log_prefix-sim.log)" >&2; tail -n 5 "$log_prefix-sim.log" >&2; status=1; }
  sim_pid=""
  sleep 0.5  # the last FORCE_N reaches the logger
  kill -0 "$estimator_pid" 2>/dev/null || { echo "demo: birotor-estimator stopped before the end (log: $log_prefix-estimator.log)" >&2; status=1; }
  stop_process birotor-estimator "$estimator_pid"
  estimator_pid=""
  if [ -n "$controller_mode" ]; then
    kill -0 "$controller_pid" 2>/dev/null || { echo "demo: birotor-controller stopped before the end (log: $log_prefix-controller.log)" >&2; status=1; }
    stop_process birotor-controller "$controller_pid"
    controller_pid=""
    grep -h "stopped:" "$log_prefix-controller.log" | sed 's/^.*\] /controller: /' || true
  fi
  stop_process lcm-logger "$logger_pid"
  logger_pid=""
  grep -h "stopped:" "$log_prefix-estimator.log" | sed 's/^.*\] /estimator: /' || true
  grep -h "simulated " "$log_prefix-sim.log" | sed 's/^.*\] /simulator: /' || true
  # Estimated against true force per rotor, from the recording.
  if ! "$eval_bin" --vehicle "$vehicle_file" --log "$flight_log" --log-level warn; then
    echo "demo: birotor-eval found no FORCE_N with its TRUTH_N in $flight_log" >&2
    status=1
  fi
  if "$review_bin" "$flight_log" --output "$log_prefix-review.html" --log-level warn > "$log_prefix-review.txt"; then
    grep "^flight: headline: \(rotor faults\|FORCE VALID\)" "$log_prefix-review.txt" || true
    echo "demo: review page: $log_prefix-review.html (recorded run: $flight_log)"
  else
    echo "demo: birotor-review failed on $flight_log" >&2
    status=1
  fi
  [ "$status" -ne 0 ] || echo "demo: done. Same figures in-process: ${eval_bin#"$repo/"} --vehicle ${vehicle_file#"$repo/"} --scenarios $scenario"
  return "$status"
}
