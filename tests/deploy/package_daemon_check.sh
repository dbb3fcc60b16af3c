#!/usr/bin/env bash
# Part of package_test.sh, run as root inside `unshare -m`: the package's
# /etc/birotor and /etc/default/birotor over /etc, an empty /var/lib (both
# overlays of this mount namespace only), then the estimator unit's ExecStart
# line (programs from the scratch root) under the user nobody: first by hand
# without /var/lib/birotor (a warning, exit 0), then as the unit with it.
# Usage: package_daemon_check.sh WORK_DIR SCRATCH_ROOT PORT
set -euo pipefail
work="$1"; root="$2"; port="$3"
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$work"
mkdir -p ov/etc-upper ov/etc-work
mount -t overlay birotor-etc -o "lowerdir=/etc,upperdir=$work/ov/etc-upper,workdir=$work/ov/etc-work" /etc
rm -rf /etc/birotor
cp -a "$root/etc/birotor" /etc/birotor
cp "$root/etc/default/birotor" /etc/default/birotor
mount -t tmpfs birotor-var-lib /var/lib

# A site file changes what the installed estimator runs: the method.
sed -i 's/^\(  method: \)ekf /\1inversion /' /etc/birotor/estimator.yaml
grep -q "^  method: inversion " /etc/birotor/estimator.yaml || fail "could not edit /etc/birotor/estimator.yaml"
XDG_CONFIG_HOME="$work/xdg" "$root/usr/bin/birotor-replay" --log hover.lcm --output est2.lcm > replay.log 2>&1 \
  || fail "installed birotor-replay with the site file: $(cat replay.log)"
grep -q "method inversion:" replay.log || fail "birotor-replay did not run the site's method: $(cat replay.log)"

# What LoadCredential= gives the unit's user: a private copy of the site key
# (the gauge state file is written and restored only under it, issue 37).
export CREDENTIALS_DIRECTORY="$work/credentials"
mkdir -p "$CREDENTIALS_DIRECTORY"
head -c 32 /dev/urandom > "$CREDENTIALS_DIRECTORY/site.key"
chown nobody:nogroup "$CREDENTIALS_DIRECTORY/site.key"
chmod 0400 "$CREDENTIALS_DIRECTORY/site.key"

# The unit's ExecStart line with /etc/default/birotor, as systemd splits it.
. "$work/unit_command_line.sh"
UNIT_OVERRIDES="BIROTOR_LCM_URL=udpm://239.255.76.67:$port?ttl=0 BIROTOR_ESTIMATOR_ARGS=--status-rate-hz=5"
unit_command_line "$root/usr/lib/systemd/system/birotor-estimator.service" /etc/default/birotor "$root"

# Stands in for systemd's notification socket: every message, one a line.
cat > notify_listener.py <<'PY'
import os, socket, sys
path, out = sys.argv[1], sys.argv[2]
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind(path)
os.chmod(path, 0o777)
s.settimeout(15)
with open(out, "w") as f:
    while True:
        try:
            message = s.recv(4096).decode()
        except socket.timeout:
            break
        f.write(message + "\n")
        f.flush()
        if message == "STOPPING=1":
            break
PY
run_daemon() {  # run_daemon LOG [DIR]: starts in DIR (the unit's WorkingDirectory), runs 1.5 s, SIGTERM as systemctl stop
  rm -f notify.sock notify.txt
  /usr/bin/python3 notify_listener.py notify.sock notify.txt &
  local listener=$!
  for _ in $(seq 50); do [ -S notify.sock ] && break; sleep 0.1; done
  # setpriv and env exec the daemon: $! is its pid. The user nobody stands in for DynamicUser.
  NOTIFY_SOCKET="$work/notify.sock" WATCHDOG_USEC=400000 setpriv --reuid=nobody --regid=nogroup --clear-groups \
    env -C "${2:-/var/lib/birotor}" "${command_line[@]}" 2> "$1" &
  local daemon=$!
  sleep 1.5
  kill -TERM "$daemon"
  local status=0
  wait "$daemon" || status=$?
  wait "$listener" || true
  [ "$status" -eq 0 ] || fail "the unit's ExecStart exited $status: $(cat "$1")"
}
# Started by hand, without the unit's StateDirectory: one warning at start,
# exit 0 at the stop (issue 39: it used to exit 1 failing to write the offsets).
run_daemon by_hand.log "$work"
grep -q "gauge offsets will not be persisted: /var/lib/birotor is missing" by_hand.log \
  || fail "no warning at start without /var/lib/birotor: $(cat by_hand.log)"
echo "ok: started by hand without /var/lib/birotor, the estimator warned at start and exited 0"
mkdir /var/lib/birotor
chown nobody:nogroup /var/lib/birotor   # what StateDirectory= does for the unit's user
run_daemon first.log
grep -qF "method inversion params /etc/birotor/estimator.yaml" first.log \
  || fail "the daemon did not run /etc/birotor/estimator.yaml: $(cat first.log)"
grep -qx "READY=1" notify.txt || fail "no READY=1: $(cat notify.txt)"
[ "$(grep -cx "WATCHDOG=1" notify.txt)" -ge 2 ] || fail "under 2 WATCHDOG=1 in 1.5 s at WATCHDOG_USEC=0.4 s: $(cat notify.txt)"
grep -qx "STOPPING=1" notify.txt || fail "no STOPPING=1: $(cat notify.txt)"
echo "ok: a file in /etc/birotor changed the installed estimator's method; READY=1, $(grep -cx "WATCHDOG=1" notify.txt) WATCHDOG=1, STOPPING=1"
state=/var/lib/birotor/gauge_offsets.yaml
[ -f "$state" ] || fail "no $state after the first run: $(cat first.log)"
[ "$(stat -c %U "$state")" = nobody ] || fail "$state belongs to $(stat -c %U "$state")"
run_daemon second.log
grep -qF "from the state file $state" second.log || fail "the restart did not read $state: $(cat second.log)"
echo "ok: the gauge offsets persisted across a restart under the user nobody ($state)"
