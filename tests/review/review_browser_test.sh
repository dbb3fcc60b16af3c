#!/usr/bin/env bash
# birotor-review's page in a real headless Chromium (Debian chromium), loaded
# from file:// with the network off at 1400 x 1000 px: a 20 s closed-loop
# flight and its replay (each chart holds the log's sample counts, counted
# here by an independent reader of the log format, and draws the rows the page
# carries); the thrust_loss, mismatch_all and a lost flight (rotor 2 at 20 %
# under the nominal controller), whose headline must answer from the first
# screen which rotor failed and when, the max tilt, lost or not and the VALID
# share; a simulator log without FORCE (said in words); the thrust_loss log
# with NaN and infinite sigmas and forces (every chart still drawn); a channel
# named with terminal escapes (no control character printed); two logs
# overlaid. No page may log to the console or raise a script error.
# The severe_gap control case's headline equals birotor-eval --control's figures.
# Usage: review_browser_test.sh TOOLS_BIN_DIR SIM_BIN_DIR (birotor-review, -replay and -eval in TOOLS_BIN_DIR)
set -euo pipefail
tools="$1"; sim="$2"
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v chromium > /dev/null || fail "no chromium (apt-get install chromium; tools/setup.sh)"
work="$(mktemp -d /tmp/birotor-review-XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
"$sim/birotor-sim" --scenario hover --controller force_feedback --set scenario.duration_s=20 --output flight.lcm \
  --log-level warn || fail "birotor-sim"
"$tools/birotor-replay" --log flight.lcm --output replay.lcm --log-level warn || fail "birotor-replay"
"$sim/birotor-sim" --scenario thrust_loss --controller force_feedback --output thrust_loss.lcm --log-level warn \
  || fail "birotor-sim thrust_loss"
"$sim/birotor-sim" --scenario mismatch_all --controller force_feedback --set scenario.duration_s=8 \
  --output mismatch.lcm --log-level warn || fail "birotor-sim mismatch_all"
"$sim/birotor-sim" --scenario thrust_loss --controller nominal --set scenario.duration_s=6 \
  --set 'faults.thrust_steps=[{time_s: 3.0, rotor: 2, scale: 0.2}]' --output lost.lcm --log-level warn \
  || fail "birotor-sim lost"
# Control case severe_gap (evaluation/control_cases.cc) as a log, and birotor-eval's figures of the same flight.
"$sim/birotor-sim" --scenario thrust_loss_severe --controller force_feedback --set scenario.duration_s=10 \
  --set 'faults.strain_gap={start_s: 5.0, duration_s: 0.5}' --output severe_gap.lcm --log-level warn \
  || fail "birotor-sim severe_gap"
"$tools/birotor-eval" --control --scenarios severe_gap --log-level warn > severe_gap.eval || fail "birotor-eval"
"$sim/birotor-sim" --scenario hover --set scenario.duration_s=2 --output sim_only.lcm --log-level warn \
  || fail "birotor-sim sim_only"
# FORCE messages 100, 200, 300 of thrust_loss with sigma +inf, sigma NaN, force NaN (issue 37).
python3 - thrust_loss.lcm bad_sigma.lcm <<'PY' || fail "writing bad_sigma.lcm"
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
at, n = 0, 0
while at + 28 <= len(data):
    _, _, _, channel_len, data_len = struct.unpack(">IqqII", data[at:at + 28])
    body = at + 28 + channel_len
    if data[at + 28:body] == b"BIROTOR_FORCE":
        n += 1
        # fingerprint 8, utime 8, seq 4, force_n[2], force_std_n[2] (lcmtypes/force_estimate_t.lcm)
        patch = {100: (body + 36, float("inf")), 200: (body + 44, float("nan")), 300: (body + 20, float("nan"))}
        if n in patch:
            struct.pack_into(">d", data, patch[n][0], patch[n][1])
    at = body + data_len
open(sys.argv[2], "wb").write(data)
PY
# A channel whose name carries terminal escapes (retitle, clear screen, bell): printed and shown as '?' (issue 37).
python3 - sim_only.lcm escape.lcm <<'PY' || fail "writing escape.lcm"
import struct, sys
data = open(sys.argv[1], "rb").read()
channel = b"BIROTOR_\x1b]0;owned\x07\x1b[2J"
payload = b"\0" * 16
event = struct.pack(">IqqII", 0xEDA1DA01, 1 << 40, 0, len(channel), len(payload)) + channel + payload
open(sys.argv[2], "wb").write(data + event)
PY
"$tools/birotor-review" escape.lcm --output escape.html > escape.counts || fail "birotor-review escape.lcm"
if LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' escape.counts escape.html; then fail "a control character reached the output"; fi
grep -qF 'BIROTOR_?]0;owned??[2J 1' escape.counts || fail "escape channel not printed as ?: $(cat -v escape.counts)"

# Loads page NAME.html in chromium; the DOM after its scripts ran in NAME.dom.
load_in_chromium() {
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
    --disable-component-update --disable-sync --user-data-dir="$work/profile-$1" --enable-logging=stderr --v=0 \
    --virtual-time-budget=10000 --window-size=1400,1000 --dump-dom "file://$work/$1.html" > "$1.dom" \
    2> "$1.chromium.log" \
    || fail "chromium exited $? on $1.html: $(tail -5 "$1.chromium.log")"
  if grep -E "CONSOLE|Uncaught" "$1.chromium.log" > console.txt; then fail "$1.html console: $(head -5 console.txt)"; fi
}
# The flight (inputs, FORCE, TRUTH, MOTOR_COMMAND) and its replay (ESTIMATOR_STATUS).
for name in flight replay thrust_loss mismatch lost severe_gap sim_only bad_sigma overlay; do
  logs="$name.lcm"
  [ "$name" = overlay ] && logs="thrust_loss.lcm lost.lcm"
  # shellcheck disable=SC2086
  "$tools/birotor-review" $logs --output "$name.html" > "$name.counts" || fail "birotor-review $logs"
  [ -s "$name.html" ] || fail "no page for $name.lcm"
  if grep -qE '(src|href)="(https?:)?//' "$name.html"; then fail "$name.html loads something from the network"; fi
  load_in_chromium "$name"
done

# The first screen as a reader sees it (kept out of the repository; the test reads its size).
chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking \
  --user-data-dir="$work/profile-shot" --virtual-time-budget=10000 --window-size=1400,1000 \
  --screenshot="$work/thrust_loss.png" "file://$work/thrust_loss.html" 2> shot.log || fail "chromium screenshot"

grep -q "^flight: position held (TRUTH" flight.counts || fail "no position figure: $(cat flight.counts)"
grep -q "^flight: [0-9]* MOTOR_COMMAND (100.0 % in force_feedback mode); [0-9]* fallbacks" flight.counts \
  || fail "no controller figure: $(cat flight.counts)"

python3 - "$work" <<'PY'
import html, json, re, struct, sys
from collections import Counter
work = sys.argv[1]

def log_counts(path):  # messages per channel, read with the format alone
    counts = Counter()
    data = open(path, "rb").read()
    at = 0
    while at + 28 <= len(data):
        sync, _, _, channel_len, data_len = struct.unpack(">IqqII", data[at:at + 28])
        assert sync == 0xEDA1DA01, f"bad sync at {at}"
        counts[data[at + 28:at + 28 + channel_len].decode()] += 1
        at += 28 + channel_len + data_len
    assert at == len(data), "trailing bytes"
    return counts

def summary_of(name):
    dom = open(f"{work}/{name}.dom").read()
    m = re.search(r'<pre id="review-summary">(.*?)</pre>', dom, re.S)
    assert m and m.group(1).strip(), f"{name}: the page's script did not finish (no summary)"
    summary = json.loads(html.unescape(m.group(1)))
    assert summary["errors"] == [], f"{name}: {summary['errors']}"
    return summary

def check(name, must_have):
    counts = log_counts(f"{work}/{name}.lcm")
    printed = dict(line.split() for line in open(f"{work}/{name}.counts")
                   if not line.startswith(("flight:", "headline:")))
    assert {k: int(v) for k, v in printed.items()} == dict(counts), f"{name}: printed {printed}, log {dict(counts)}"
    summary = summary_of(name)
    charts = {c["id"]: c for c in summary["charts"]}
    page = json.loads(re.search(r"var REVIEW = (\{.*?\});\n", open(f"{work}/{name}.html").read(), re.S).group(1))
    rows = {c["id"]: c["rows"] for c in page["charts"]}
    c = lambda channel: counts["BIROTOR_" + channel]
    inputs = c("STRAIN") + c("MOTOR") + c("IMU") + c("POSE")
    expected = {"forces": c("FORCE") + c("TRUTH"), "thrust": c("FORCE") + c("TRUTH"), "status": c("FORCE"),
                "nis": c("ESTIMATOR_STATUS"), "fusion": c("ESTIMATOR_STATUS"), "rates": inputs, "gaps": inputs,
                "position": c("POSE") + c("TRUTH") + c("SETPOINT"), "attitude": c("POSE") + c("TRUTH"),
                "pitch_rate": c("IMU"), "commands": c("MOTOR_COMMAND"),
                "controller_lanes": c("MOTOR_COMMAND"), "controller_counts": c("CONTROLLER_STATUS")}
    for chart in must_have:
        assert chart in charts, f"{name}: no chart {chart} in the loaded page: {list(charts)}"
    for chart, n in expected.items():
        if n == 0:
            assert chart not in charts, f"{name}: chart {chart} without data"
            continue
        assert chart in charts, f"{name}: no chart {chart} in the loaded page: {list(charts)}"
        assert charts[chart]["samples"] == n, f"{name} {chart}: {charts[chart]['samples']} samples, log {n}"
    for chart, g in charts.items():
        assert g["rows"] == rows[chart] > 0, f"{name} {chart}: dygraph holds {g['rows']} rows, the page {rows[chart]}"
    print(f"ok: {name}: {len(charts)} charts loaded in chromium without console errors, each with the log's "
          f"samples ({', '.join(f'{k} {v}' for k, v in sorted(counts.items()))})")
    return summary

def headline(name, expected, column=0):
    """The headline as the browser rendered it: each row's answer must match its regex."""
    summary = summary_of(name)
    rows = {question: answers[column] for question, answers in summary["headline"].items()}
    for question, pattern in expected.items():
        assert re.search(pattern, rows.get(question, "")), f"{name} headline {question!r}: {rows.get(question)!r}"
    print(f"ok: {name} headline: {rows}")
    return summary

check("flight", ["forces", "thrust", "status", "rates", "gaps", "position", "attitude", "pitch_rate", "commands",
                 "controller_lanes"])
check("replay", ["forces", "thrust", "status", "nis", "fusion"])
# Target (issue 39): from the first screen, which rotor failed and when, the max tilt, lost or not, VALID or not.
# Rotor 2 steps to 0.75 at 5 s (config/scenarios/thrust_loss.yaml); the estimator says ROTOR2_FAULT 15 ms later
# (5.015 s measured); tilt 0.017 rad measured (birotor-eval --control --scenarios thrust_loss: peak tilt 0.0171
# rad and 0 fallbacks in force_feedback, the same figures).
tl = check("thrust_loss", ["forces", "position", "attitude", "status", "thrust", "commands"])
headline("thrust_loss", {"lost": r"^no \(TRUTH\)$",
                         "rotor faults": r"^rotor 2 thrust 1\.00 -> 0\.7\d at 5\.000 s \(TRUTH\); ROTOR2_FAULT at 5\.0[0-4]\d s$",
                         "max tilt": r"^0\.0[0-3]\d rad", "FORCE VALID": r"^(99\.\d|100\.0) % ",
                         "fallbacks": r"^0; in the fallback in 0\.\d % of MOTOR_COMMAND; FORCE flown on from 0\.0\d\d s$",
                         "filter resets": r"^none after the start-up reset$"})
assert tl["headline_bottom_px"] <= 1000, f"headline below the first screen: {tl['headline_bottom_px']} px"
assert tl["first_chart_top_px"] < 1000, f"forces chart not on the first screen: {tl['first_chart_top_px']} px"
assert tl["path"] == 1, "no x-z path"
# mismatch_all: MODEL_MISMATCH 11 ms in (measured), VALID withdrawn (3 of 8000 measured).
headline("mismatch", {"lost": r"^no", "rotor faults": r"^none$",
                      "FORCE VALID": r"^0\.\d % \(\d+ of 8000 estimates\); MODEL_MISMATCH at 0\.0\d\d s$",
                      "fallbacks": r"in the fallback in 100\.0 % of MOTOR_COMMAND; FORCE never flown on$"})
# Rotor 2 at 20 % from 3 s under the nominal map: 19.6 m down by 6 s (measured), lost.
headline("lost", {"lost": r"^yes, from 3\.\d{3} s \(TRUTH\)$",
                  "rotor faults": r"^rotor 2 thrust 1\.00 -> 0\.20 at 3\.000 s \(TRUTH\); ROTOR2_FAULT at 3\.0\d\d s$",
                  "altitude loss": r"^1\d\.\d{3} m at 5\.9\d\d s$", "fallbacks": r"^0$"})
# The headline's figures equal birotor-eval's on the same flight: peak tilt, fallbacks and peak altitude loss
# of its control table (eval's loss counts from the fault; the largest loss here is after it: 0.2602 m).
row = next(l for l in open(f"{work}/severe_gap.eval") if l.startswith("| severe_gap seed") and "| force_feedback |" in l)
cells = [c.strip() for c in row.strip().strip("|").split("|")]
eval_tilt, eval_loss, eval_fallbacks = float(cells[3]), float(cells[7]), int(cells[-2])
sg = headline("severe_gap", {"fallbacks": rf"^{eval_fallbacks}( |;|$)"})
tilt = float(re.match(r"([0-9.]+) rad", sg["headline"]["max tilt"][0]).group(1))
# The headline rounds to 3 decimals, birotor-eval to 4: equal within both roundings.
rounding = 0.0005 + 0.00005 + 1e-9
assert abs(tilt - eval_tilt) <= rounding, f"max tilt {tilt} rad, birotor-eval {eval_tilt} rad"
loss = float(re.match(r"([0-9.]+) m", sg["headline"]["altitude loss"][0]).group(1))
assert abs(loss - eval_loss) <= rounding, f"altitude loss {loss} m, birotor-eval {eval_loss} m"
print(f"ok: severe_gap: max tilt {tilt} rad, altitude loss {loss} m, {eval_fallbacks} fallbacks: birotor-eval's")
headline("sim_only", {"FORCE VALID": r"^no FORCE in this log$", "fallbacks": r"^no MOTOR_COMMAND in this log$"})
assert "No FORCE: this log holds no force estimate" in open(f"{work}/sim_only.dom").read()
bad = summary_of("bad_sigma")
assert [c["id"] for c in bad["charts"]] == [c["id"] for c in tl["charts"]], "a NaN or inf sigma lost a chart"
assert all(c["rows"] > 0 for c in bad["charts"])
print(f"ok: bad_sigma: {len(bad['charts'])} charts drawn with inf and NaN in FORCE")
headline("overlay", {"lost": r"^no"}, 0)
ov = headline("overlay", {"lost": r"^yes"}, 1)
ids = [c["id"] for c in ov["charts"]]
assert "status" in ids and "status_B" in ids and "controller_lanes_B" in ids, ids

# The screenshot of the first screen: a PNG of 1400 x 1000 px.
png = open(f"{work}/thrust_loss.png", "rb").read()
assert png[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", png[16:24]) == (1400, 1000), "screenshot"
PY
echo "PASS ($(du -k flight.html | cut -f1) kB page for 20 s)"
