#!/usr/bin/env bash
# Issue 24 item 5: the programs' error paths say one line and the documented
# exit status, before doing any work: 1 for a missing or bad file or data, 2
# for a bad command line (transport/program_options.h).
# Usage: program_errors_test.sh TOOLS_BIN_DIR SIM_BIN_DIR
set -euo pipefail
tools="$1"; sim="$2"
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
work="$(mktemp -d /tmp/birotor-errors-XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
# expect STATUS PATTERN command...: exit status, stderr one line matching PATTERN, nothing on stdout.
expect() {
  local want="$1" pattern="$2"; shift 2
  local status=0
  timeout 60 "$@" > out.txt 2> err.txt || status=$?
  local shown="$(basename "$1") ${*:2}"
  [ "$status" -eq "$want" ] || { fail "$shown: exit $status, want $want: $(head -c 300 err.txt)"; return; }
  [ "$(grep -c . err.txt)" -eq 1 ] || fail "$shown: stderr is not one line: $(head -c 300 err.txt)"
  grep -qE "$pattern" err.txt || fail "$shown: stderr '$(cat err.txt)' lacks /$pattern/"
  [ ! -s out.txt ] || fail "$shown: printed before the error: $(head -c 200 out.txt)"
}
"$sim/birotor-sim" --scenario hover --set scenario.duration_s=0.5 --output in.lcm --log-level warn
"$tools/birotor-replay" --log in.lcm --output replay.lcm --log-level warn

# birotor-analyze --measure with an unknown state: the error, and nothing of the analysis.
expect 2 "^birotor-analyze: error: --measure: unknown state 'b3'" "$tools/birotor-analyze" --measure b1,b3

# birotor-analyze --vehicle: a description that cannot be read names the file
# and the key; --without-gauge is checked against the vehicle's arms before
# anything is printed, and needs --vehicle.
cat > bad_vehicle.yaml <<'YAML'
vehicle:
  name: bad
  body_mass_kg: -4.0
YAML
expect 1 "^birotor-analyze: error: bad_vehicle.yaml: .*body_mass_kg" "$tools/birotor-analyze" --vehicle bad_vehicle.yaml
trirotor="$source_dir/config/vehicles/trirotor.yaml"
expect 2 "^birotor-analyze: error: --without-gauge: arm 4 is not an arm of trirotor \(arms 1 to 3\)" \
  "$tools/birotor-analyze" --vehicle "$trirotor" --without-gauge 4
expect 2 "^birotor-analyze: error: --without-gauge: arm 0 is not an arm" \
  "$tools/birotor-analyze" --vehicle "$trirotor" --without-gauge 0
expect 2 "^birotor-analyze: error: --without-gauge: no gauge would remain" \
  "$tools/birotor-analyze" --vehicle "$trirotor" --without-gauge 1,2 --without-gauge 3
expect 2 "^birotor-analyze: error: --without-gauge requires --vehicle" "$tools/birotor-analyze" --without-gauge 1
expect 2 "^birotor-analyze: error: --measure excludes --vehicle" "$tools/birotor-analyze" --vehicle "$trirotor" \
  --measure x,z

# Offline programs have no --lcm-url (it was listed and ignored: garbage://x exited 0).
for program in birotor-replay birotor-plot birotor-eval birotor-identify; do
  expect 2 "^$program: error: .*--lcm-url" "$tools/$program" --lcm-url garbage://x --log in.lcm
done

# A missing file exits 1 everywhere, naming the file.
expect 1 "^birotor-replay: error: .*missing.lcm" "$tools/birotor-replay" --log missing.lcm --output o.lcm
expect 1 "^birotor-plot: error: .*missing.lcm" "$tools/birotor-plot" --log missing.lcm --png o.png
expect 1 "^birotor-plot: error: .*missing.yaml" "$tools/birotor-plot" --log replay.lcm --png o.png --params missing.yaml
expect 1 "^birotor-eval: error: .*missing.lcm" "$tools/birotor-eval" --log missing.lcm
expect 1 "^birotor-identify: error: .*missing.lcm" "$tools/birotor-identify" --log missing.lcm --output v.yaml \
  --log-level warn
expect 1 "^birotor-identify: error: .*missing.yaml" "$tools/birotor-identify" --log in.lcm --update-params missing.yaml \
  --log-level warn
# A vehicle the program's model cannot fly is refused at load, naming file, key and reason.
expect 1 "^birotor-identify: error: .*trirotor.yaml: key 'vehicle': birotor-identify runs the birotor's model.*arm_count is 3" \
  "$tools/birotor-identify" --params "$trirotor" --log in.lcm --output v.yaml --log-level warn
# --vehicle (an N-arm bench fit): a log without the counted channels, and --update-params, are refused.
expect 1 "^birotor-identify: error: refused: in.lcm has no STRAIN_N, MOTOR_N or LOADCELL_N samples" \
  "$tools/birotor-identify" --vehicle "$trirotor" --log in.lcm --output v.yaml --log-level warn
expect 1 "^birotor-identify: error: --vehicle writes --output FILE \(not --update-params\)" \
  "$tools/birotor-identify" --vehicle "$trirotor" --log in.lcm --update-params v.yaml --log-level warn
expect 1 "^birotor-monitor: error: .*missing.yaml" "$tools/birotor-monitor" --scenario missing.yaml \
  --lcm-url "udpm://239.255.76.67:7799?ttl=0"
expect 1 "^birotor-analyze: error: .*missing.yaml" "$tools/birotor-analyze" --params missing.yaml
expect 1 "^birotor-analyze: error: .*missing.yaml" "$tools/birotor-analyze" --vehicle missing.yaml
expect 1 "^birotor-review: error: .*missing.lcm" "$tools/birotor-review" missing.lcm --output o.html
expect 1 "^birotor-sim: error: .*missing.yaml" "$sim/birotor-sim" --scenario missing.yaml --output o.lcm

# A misspelt scenario name lists the scenarios.
expect 1 "^birotor-sim: error: unknown scenario 'hovr' \(scenarios: .*hover.*\)" \
  "$sim/birotor-sim" --scenario hovr --output o.lcm
expect 1 "^birotor-eval: error: unknown scenario 'hovr' \(scenarios: .*hover.*\)" "$tools/birotor-eval" --scenarios hovr

# birotor-eval --vehicle: a named scenario whose per-arm list does not fit
# the vehicle is an error naming the scenario and the key, before any row;
# in the default list it is skipped with that reason under the table.
expect 1 "^birotor-eval: error: gauge_offset: .*gauge.offset_rad.*3 elements" \
  "$tools/birotor-eval" --vehicle "$trirotor" --scenarios gauge_offset --methods inversion
timeout 300 "$tools/birotor-eval" --vehicle "$trirotor" --methods inversion --duration-s 0.2 > defaults.txt 2> err.txt ||
  fail "birotor-eval --vehicle with the default scenarios: exit $?: $(head -c 300 err.txt)"
grep -q "^skipped: gauge_offset: .*gauge.offset_rad" defaults.txt || fail "no skipped gauge_offset: $(tail -c 300 defaults.txt)"
grep -q "^| hover | inversion |" defaults.txt || fail "no hover row: $(head -c 300 defaults.txt)"

# birotor-eval --log on a replay output: no inputs to estimate from (it said "0 FORCE").
expect 1 "^birotor-eval: error: replay.lcm: no STRAIN, MOTOR, IMU or POSE input .*birotor-replay output" \
  "$tools/birotor-eval" --log replay.lcm

[ "$failures" -eq 0 ] || { echo "$failures failures" >&2; exit 1; }
echo PASS
