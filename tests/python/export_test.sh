#!/usr/bin/env bash
# birotor-export and the Python package with the system python3: a closed-loop
# flight log from birotor-sim (inputs, TRUTH, FORCE, MOTOR_COMMAND) and its
# replay (ESTIMATOR_STATUS), exported to CSV and read with birotor.read_log. Every message is in the CSVs and in the DataFrames:
# the counts equal those of birotor-review's C++ reader; headers carry units;
# every field of a FORCE is a column, with time_s and one column per status
# bit; CSV and DataFrame hold the same values; DataFrame.attrs carry the units.
# Usage: export_test.sh PYTHON_DIR SIM_BIN_DIR TOOLS_BIN_DIR (birotor-review, birotor-replay)
set -euo pipefail
python_dir="$(cd "$1" && pwd -P)"; sim="$2"; review="$3"
fail() { echo "FAIL: $*" >&2; exit 1; }
work="$(mktemp -d /tmp/birotor-export-XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
"$sim/birotor-sim" --scenario hover --controller force_feedback --set scenario.duration_s=5 --output flight.lcm \
  --log-level warn || fail "birotor-sim"
"$review/birotor-replay" --log flight.lcm --output replay.lcm --log-level warn || fail "birotor-replay"
export PYTHONPATH="$python_dir"
for name in flight replay; do
  "$review/birotor-review" $name.lcm --output $name.html > $name.counts || fail "birotor-review $name.lcm"
  /usr/bin/python3 "$python_dir/birotor-export" $name.lcm --output-dir $name > $name.export || fail "birotor-export $name.lcm"
done

# Exit statuses: a missing log 1, a bad command line 2.
status=0; /usr/bin/python3 "$python_dir/birotor-export" missing.lcm --output-dir x 2> err.txt || status=$?
[ "$status" -eq 1 ] || fail "missing log exited $status"
grep -q "^birotor-export: error: missing.lcm: no such file$" err.txt || fail "missing log said: $(cat err.txt)"
status=0; /usr/bin/python3 "$python_dir/birotor-export" flight.lcm 2> /dev/null || status=$?
[ "$status" -eq 2 ] || fail "no --output-dir exited $status"

/usr/bin/python3 - "$work" <<'PY'
import csv, sys
import birotor
work = sys.argv[1]
total, channels = 0, 0
for name in ("flight", "replay"):
    expected = {line.split()[0]: int(line.split()[1]) for line in open(f"{work}/{name}.counts")
                if not line.startswith("flight:")}
    frames = birotor.read_log(f"{work}/{name}.lcm")
    assert set(frames) == set(expected), (name, sorted(frames), sorted(expected))
    for channel, n in sorted(expected.items()):
        with open(f"{work}/{name}/{channel}.csv", newline="") as f:
            rows = list(csv.reader(f))
        assert len(rows) - 1 == n, f"{name} {channel}: {len(rows) - 1} CSV rows, log {n}"
        assert len(frames[channel]) == n, f"{name} {channel}: {len(frames[channel])} DataFrame rows, log {n}"
        assert len(rows[0]) == len(frames[channel].columns), f"{name} {channel}: CSV and DataFrame columns differ"
        total += n
        channels += 1
frames = birotor.read_log(f"{work}/flight.lcm")
force = frames["BIROTOR_FORCE"]
header = next(csv.reader(open(f"{work}/flight/BIROTOR_FORCE.csv")))
# force_estimate_t: utime, seq, force_n[2], force_std_n[2], thrust_scale[2] (a ratio), status and its 11
# STATUS_* bits; before them log_utime and time_s.
bits = ["STATUS_VALID", "STATUS_CONVERGING", "STATUS_MEASUREMENT_REJECTED", "STATUS_INPUT_STALE", "STATUS_ROTOR1_FAULT",
        "STATUS_ROTOR2_FAULT", "STATUS_FILTER_RESET", "STATUS_NO_MOTOR_INPUT", "STATUS_THRUST_DEFICIT",
        "STATUS_INPUT_CONFLICT", "STATUS_MODEL_MISMATCH"]
assert header == ["log_utime [us]", "time_s [s]", "utime [us]", "seq", "force_n[0] [N]", "force_n[1] [N]",
                  "force_std_n[0] [N]", "force_std_n[1] [N]", "thrust_scale[0]", "thrust_scale[1]", "status"] + bits, header
for bit in bits:  # each bit column is its bit of status, in the CSV (0/1) and the DataFrame (bool)
    value = getattr(birotor.force_estimate_t, bit)
    assert list(force[bit]) == [bool(s & value) for s in force["status"]], bit
    assert force[bit].dtype == bool, (bit, force[bit].dtype)
# The simulated clock: FORCE at 1 kHz from the log's first event (t = 0), 5 s.
assert force["time_s"].iloc[0] == 0.0 and abs(force["time_s"].iloc[-1] - 4.999) < 1e-9, force["time_s"].iloc[[0, -1]]
assert list(force["time_s"]) == [(u - force["log_utime"].iloc[0]) / 1e6 for u in force["log_utime"]]
assert force["STATUS_VALID"].iloc[-1], "the 5 s hover ends valid"
assert force.attrs["units"]["force_n[0]"] == "N" and force.attrs["units"]["time_s"] == "s", force.attrs
assert force.attrs["type"] == "force_estimate_t" and force.attrs["channel"] == "BIROTOR_FORCE", force.attrs
assert birotor.column_unit("force_estimate_t", "force_std_n[1]") == "N"
assert birotor.column_unit("estimator_status_t", "inputs[0].age_s") == "s"
assert birotor.column_unit(birotor.estimator_status_t, "accelerometer.rate_hz") == "Hz"
status_frame = birotor.read_log(f"{work}/replay.lcm")["BIROTOR_ESTIMATOR_STATUS"]
assert "STATUS_VALID" in status_frame.columns, "ESTIMATOR_STATUS carries FORCE's bits"
status_header = next(csv.reader(open(f"{work}/replay/BIROTOR_ESTIMATOR_STATUS.csv")))
for column in ("inputs[3].nis_mean", "inputs[0].age_s [s]", "accelerometer.rate_hz [Hz]", "method"):
    assert column in status_header or any(h.startswith(column) for h in status_header), column
values = [float(r[header.index("force_n[0] [N]")]) for r in list(csv.reader(open(f"{work}/flight/BIROTOR_FORCE.csv")))[1:]]
assert values == list(force["force_n[0]"]), "CSV and DataFrame force_n[0] differ"
print(f"ok: {total} messages on {channels} channels of two logs, equal counts in the CSVs, the DataFrames and the log")
PY
echo PASS
