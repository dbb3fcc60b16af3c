#!/usr/bin/env bash
# The Python package installed with pip, offline, as docs/review.md "Install
# with pip" says: a venv with Debian's numpy and pandas (--system-site-packages),
# `pip install --no-index --no-build-isolation python/` (--no-index: pip may
# not download anything), from a copy of the repository's python/ and
# lcmtypes/ (pip builds in place; the source tree stays clean). Then the
# venv's birotor-export and birotor.read_log on a simulated log: seconds,
# decoded bits, units, and the version the project's CMakeLists.txt names.
# Usage: venv_install_test.sh SOURCE_DIR SIM_BIN_DIR PROJECT_VERSION
set -euo pipefail
source_dir="$1"; sim="$2"; version="$3"
fail() { echo "FAIL: $*" >&2; exit 1; }
work="$(mktemp -d /tmp/birotor-venv-XXXXXX)"
trap 'rm -rf "$work"' EXIT
mkdir "$work/repo"
cp -r "$source_dir/python" "$source_dir/lcmtypes" "$work/repo/"
rm -rf "$work/repo/python/build" "$work/repo/python/"*.egg-info
cd "$work"
/usr/bin/python3 -m venv --system-site-packages venv || fail "python3 -m venv (Debian python3-venv)"
PIP_NO_INDEX=1 venv/bin/pip install --no-index --no-build-isolation --no-input --quiet ./repo/python \
  || fail "pip install"
[ "$(venv/bin/birotor-export --version)" = "birotor-export $version" ] || fail "version: $(venv/bin/birotor-export --version)"
"$sim/birotor-sim" --scenario hover --controller force_feedback --set scenario.duration_s=2 --output flight.lcm --log-level warn || fail "birotor-sim"
venv/bin/birotor-export flight.lcm --output-dir csv > export.txt || fail "venv birotor-export"
head -1 csv/BIROTOR_FORCE.csv | grep -q '^log_utime \[us\],time_s \[s\],utime \[us\],.*,status,STATUS_VALID,' \
  || fail "FORCE header: $(head -1 csv/BIROTOR_FORCE.csv)"
# Run outside the copy so the import is the venv's installed package.
(cd / && "$work/venv/bin/python" - "$work" <<'PY'
import sys
import birotor
work = sys.argv[1]
assert birotor.__file__.startswith(f"{work}/venv/"), birotor.__file__
force = birotor.read_log(f"{work}/flight.lcm")["BIROTOR_FORCE"]
# birotor-sim: FORCE per strain sample at 1 kHz for 2 s, from t = 0.
assert len(force) == 2000 and force["time_s"].iloc[-1] == 1.999, (len(force), force["time_s"].iloc[-1])
assert force.attrs["units"]["force_n[1]"] == "N" and force["STATUS_VALID"].dtype == bool
print(f"ok: venv package {birotor.__version__}, {len(force)} FORCE rows, {int(force['STATUS_VALID'].sum())} valid")
PY
) || fail "read_log in the venv"
echo PASS
