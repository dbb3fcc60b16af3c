#!/usr/bin/env bash
# birotor-review's page in a real headless Chromium (Debian chromium): a 20 s
# closed-loop flight from birotor-sim, its review page loaded from file://
# with the network off; the page must load without a console error, and each
# chart must hold the log's sample counts (counted here by an independent
# reader of the log format) and draw the rows the page carries.
# Usage: review_browser_test.sh TOOLS_BIN_DIR SIM_BIN_DIR (birotor-review and birotor-replay in TOOLS_BIN_DIR)
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

# Loads page NAME.html in chromium; the DOM after its scripts ran in NAME.dom.
load_in_chromium() {
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
    --disable-component-update --disable-sync --user-data-dir="$work/profile-$1" --enable-logging=stderr --v=0 \
    --virtual-time-budget=10000 --dump-dom "file://$work/$1.html" > "$1.dom" 2> "$1.chromium.log" \
    || fail "chromium exited $? on $1.html: $(tail -5 "$1.chromium.log")"
  if grep -E "CONSOLE|Uncaught" "$1.chromium.log" > console.txt; then fail "$1.html console: $(head -5 console.txt)"; fi
}
# The flight (inputs, FORCE, TRUTH, MOTOR_COMMAND) and its replay (ESTIMATOR_STATUS).
for name in flight replay; do
  "$tools/birotor-review" "$name.lcm" --output "$name.html" > "$name.counts" || fail "birotor-review $name.lcm"
  [ -s "$name.html" ] || fail "no page for $name.lcm"
  if grep -qE '(src|href)="(https?:)?//' "$name.html"; then fail "$name.html loads something from the network"; fi
  load_in_chromium "$name"
done

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

def check(name, must_have):
    counts = log_counts(f"{work}/{name}.lcm")
    printed = dict(line.split() for line in open(f"{work}/{name}.counts") if not line.startswith("flight:"))
    assert {k: int(v) for k, v in printed.items()} == dict(counts), f"{name}: printed {printed}, log {dict(counts)}"
    dom = open(f"{work}/{name}.dom").read()
    m = re.search(r'<pre id="review-summary">(.*?)</pre>', dom, re.S)
    assert m and m.group(1).strip(), f"{name}: the page's script did not finish (no summary)"
    summary = json.loads(html.unescape(m.group(1)))
    assert summary["errors"] == [], summary["errors"]
    charts = {c["id"]: c for c in summary["charts"]}
    page = json.loads(re.search(r"var REVIEW = (\{.*?\});\n", open(f"{work}/{name}.html").read(), re.S).group(1))
    rows = {c["id"]: c["rows"] for c in page["charts"]}
    c = lambda channel: counts["BIROTOR_" + channel]
    inputs = c("STRAIN") + c("MOTOR") + c("IMU") + c("POSE")
    expected = {"forces": c("FORCE") + c("TRUTH"), "thrust": c("FORCE") + c("TRUTH"), "status": c("FORCE"),
                "nis": c("ESTIMATOR_STATUS"), "fusion": c("ESTIMATOR_STATUS"), "rates": inputs, "gaps": inputs,
                "position": c("POSE") + c("TRUTH"), "commands": c("MOTOR_COMMAND"),
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

check("flight", ["forces", "thrust", "status", "rates", "gaps", "position", "commands", "controller_lanes"])
check("replay", ["forces", "thrust", "status", "nis", "fusion"])
PY
echo "PASS ($(du -k flight.html | cut -f1) kB page for 20 s)"
