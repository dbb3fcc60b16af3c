#!/usr/bin/env bash
# Installs the build into a temporary prefix and runs every installed program
# with its defaults from another directory, with the source and build trees
# out of reach: a private mount namespace (unshare -m) with an empty tmpfs
# over both. Needs root for the namespace; otherwise it says so and exits 77
# (CTest: skipped). Also checks that no installed file names the source or
# build tree, and that the estimator's unit verifies (systemd-analyze, when
# present) and its ExecStart line starts the daemon.
# Usage: installed_programs_test.sh SOURCE_DIR BUILD_DIR [PORT]
set -euo pipefail
source_dir="$(cd "$1" && pwd -P)"
build_dir="$(cd "$2" && pwd -P)"
port=$(( ${3:-7795} + ${BIROTOR_TEST_PORT_OFFSET:-0} ))  # several checkouts testing at once

if [ "$(id -u)" -ne 0 ] || ! unshare -m true 2> /dev/null; then
  echo "SKIPPED: needs root and unshare -m to hide the source tree (run ctest as root)"
  exit 77
fi

work="$(mktemp -d /tmp/birotor-installed-XXXXXX)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
cmake --install "$build_dir" --prefix "$prefix" > "$work/install.log"

fail() { echo "FAIL: $*" >&2; exit 1; }

# 1. No installed file names the source or the build tree.
if grep -rlF -e "$source_dir" -e "$build_dir" "$prefix" > "$work/named.txt"; then
  fail "installed files name the source or build tree: $(tr '\n' ' ' < "$work/named.txt")"
fi
echo "ok: no installed file names $source_dir or $build_dir"

# 2. The rest runs in a private mount namespace where both trees are empty.
cat > "$work/inside.sh" <<'INSIDE'
set -euo pipefail
prefix="$1"; source_dir="$2"; build_dir="$3"; port="$4"
fail() { echo "FAIL: $*" >&2; exit 1; }
mount -t tmpfs birotor-hidden "$source_dir"
[ -d "$build_dir" ] && mount -t tmpfs birotor-hidden "$build_dir"
[ -z "$(ls -A "$source_dir")" ] || fail "the source tree is still visible"
mkdir -p "$prefix/../run" && cd "$prefix/../run"
export XDG_CONFIG_HOME="$PWD/xdg"   # no user files: the shipped ones are used
[ -e /etc/birotor ] && echo "note: /etc/birotor exists and comes before the shipped files"
bin="$prefix/bin"
url="udpm://239.255.76.67:$port?ttl=0"

# Every program answers --help; the default files are the installed ones.
for program in "$bin"/*; do
  "$program" --help > help.txt 2>&1 || fail "$(basename "$program") --help exited $?"
done
"$bin/birotor-estimator" --help | grep -qF "$prefix/share/birotor/config/estimator.yaml" \
  || fail "birotor-estimator --help does not show the installed estimator.yaml"
echo "ok: --help of $(ls "$bin" | wc -l) programs"

# Real short runs with the defaults.
"$bin/birotor-sim" --scenario hover --set scenario.duration_s=1 --output hover.lcm --log-level warn \
  || fail "birotor-sim hover"
"$bin/birotor-replay" --log hover.lcm --output est.lcm --csv est.csv --log-level warn || fail "birotor-replay"
[ "$(wc -l < est.csv)" -gt 900 ] || fail "birotor-replay wrote $(wc -l < est.csv) CSV lines"
"$bin/birotor-plot" --log est.lcm --png est.png > /dev/null || fail "birotor-plot"
"$bin/birotor-eval" --scenarios hover --methods ekf --duration-s 1 --log-level warn > eval.md || fail "birotor-eval"
grep -q "| hover | ekf |" eval.md || fail "birotor-eval table: $(cat eval.md)"
"$bin/birotor-analyze" > analyze.txt || fail "birotor-analyze"
grep -q "Parameter file: $prefix/share/birotor/config/reference_vehicle.yaml" analyze.txt \
  || fail "birotor-analyze did not use the installed reference vehicle"
"$bin/birotor-sim" --scenario bench --set scenario.duration_s=12 --output bench.lcm --log-level warn \
  || fail "birotor-sim bench"
"$bin/birotor-identify" --log bench.lcm --output vehicle.yaml --log-level warn || fail "birotor-identify"
grep -q "arm_stiffness_n_m_rad" vehicle.yaml || fail "birotor-identify wrote no vehicle section"
"$bin/birotor-identify" --log bench.lcm --output vehicle2.yaml --config "$prefix/share/birotor/config/identification.yaml" \
  --log-level warn || fail "birotor-identify --config identification.yaml"
echo "ok: sim, replay, plot, eval, analyze, identify ran with their defaults"

# The estimator's unit: verify it, then start its ExecStart line by hand with
# the installed environment file (the URL moved to a private port).
unit="$prefix/share/birotor/deploy/birotor-estimator.service"
env_file="$prefix/share/birotor/deploy/birotor.env"
grep -q "^ExecStart=$prefix/bin/birotor-estimator " "$unit" || fail "ExecStart of $unit is not under $prefix"
if command -v systemd-analyze > /dev/null; then
  for u in "$unit" "$prefix/share/birotor/deploy/birotor-sim.service" \
           "$prefix/share/birotor/deploy/birotor-controller.service"; do
    # MANPATH: verify runs `man` on the unit's Documentation=man:... page, the installed one.
    MANPATH="$prefix/share/man" systemd-analyze verify "$u" > verify.txt 2>&1 || fail "systemd-analyze verify $u: $(cat verify.txt)"
    if grep -v "^$" verify.txt | grep -q .; then fail "systemd-analyze verify $u: $(cat verify.txt)"; fi
  done
  echo "ok: systemd-analyze verify of the units"
else
  echo "note: no systemd-analyze here; the units were not verified"
fi
# What LoadCredential= gives the unit: its private copy of the site key
# (the daemon does not start without it).
export CREDENTIALS_DIRECTORY="$PWD/credentials"
mkdir -p "$CREDENTIALS_DIRECTORY"
(umask 077 && head -c 32 /dev/urandom > "$CREDENTIALS_DIRECTORY/site.key")
. "$prefix/../unit_command_line.sh"
UNIT_OVERRIDES="BIROTOR_LCM_URL=$url BIROTOR_ESTIMATOR_ARGS=--status-rate-hz=5"
unit_command_line "$unit" "$env_file"
"${command_line[@]}" 2> estimator.log &
daemon=$!
sleep 1.5
kill -TERM "$daemon"   # what systemctl stop sends
status=0
wait "$daemon" || status=$?
[ "$status" -eq 0 ] || fail "the unit's ExecStart exited $status: $(cat estimator.log)"
grep -qF "params $prefix/share/birotor/config/estimator.yaml" estimator.log \
  || fail "the daemon did not load the installed estimator.yaml: $(cat estimator.log)"
echo "ok: the unit's ExecStart started birotor-estimator and it stopped cleanly on SIGTERM"
INSIDE
cp "$source_dir/tests/deploy/unit_command_line.sh" "$work/"
unshare -m --propagation private bash "$work/inside.sh" "$prefix" "$source_dir" "$build_dir" "$port"
echo "PASS"
