#!/usr/bin/env bash
# The Debian package: builds it with `cpack -G DEB` from the build tree,
# checks its name, contents (a manual page per program, copyright, changelog),
# lintian (no error), conffiles and maintainer scripts (no restart on upgrade), unpacks it into
# a scratch root (dpkg-deb -x) and runs the installed programs there (every
# --help, a short simulation and replay), verifies the installed units with
# `systemd-analyze verify`. As root it then, in a private mount
# namespace (overlays on /etc and /var/lib, nothing outside changes), shows
# that a file in /etc/birotor changes what the installed estimator runs, that
# the daemon started by the unit's ExecStart line says READY=1 and WATCHDOG=1
# to NOTIFY_SOCKET, and that its gauge offsets persist across a restart under
# an unprivileged user (nobody, for the unit's DynamicUser). Not root: that
# part is skipped (exit 77) after the rest passed.
# Usage: package_test.sh BUILD_DIR VERSION [PORT]
set -euo pipefail
build_dir="$(cd "$1" && pwd -P)"
version="$2"
port=$(( ${3:-7797} + ${BIROTOR_TEST_PORT_OFFSET:-0} ))
source_dir="$(cd "$(dirname "$0")/../.." && pwd -P)"
fail() { echo "FAIL: $*" >&2; exit 1; }

work="$(mktemp -d /tmp/birotor-package-XXXXXX)"
trap 'rm -rf "$work"' EXIT
chmod 755 "$work"   # the unprivileged run below reaches the programs through it

# 1. The package and its name.
(cd "$build_dir" && cpack -G DEB -B "$work/cpack" > "$work/cpack.log" 2>&1) || fail "cpack: $(tail -20 "$work/cpack.log")"
arch="$(dpkg --print-architecture)"
deb="$work/cpack/birotor_${version}_${arch}.deb"
[ -f "$deb" ] || fail "no $deb; cpack made: $(ls "$work/cpack")"
echo "ok: $(basename "$deb") ($(du -k "$deb" | cut -f1) kB)"
[ "$(dpkg-deb -f "$deb" Package)" = birotor ] || fail "Package: $(dpkg-deb -f "$deb" Package)"
dpkg-deb -f "$deb" Depends | grep -q "python3" || fail "Depends lacks python3: $(dpkg-deb -f "$deb" Depends)"
dpkg-deb -f "$deb" Depends | grep -q "liblcm" || fail "Depends lacks liblcm (shlibdeps): $(dpkg-deb -f "$deb" Depends)"

# 2. Contents.
dpkg-deb -c "$deb" | awk '{print $NF}' | sed 's|^\./|/|' > "$work/contents.txt"
for path in /usr/bin/birotor-estimator /usr/bin/birotor-controller /usr/bin/birotor-sim /usr/bin/birotor-replay \
            /usr/bin/birotor-identify /usr/bin/birotor-eval /usr/bin/birotor-plot /usr/bin/birotor-analyze \
            /usr/bin/birotor-monitor /usr/bin/birotor-latency-probe /usr/bin/birotor-lcm-spy \
            /etc/birotor/estimator.yaml /etc/birotor/controller.yaml /etc/birotor/identification.yaml \
            /etc/birotor/reference_vehicle.yaml /etc/default/birotor \
            /usr/lib/systemd/system/birotor-estimator.service /usr/lib/systemd/system/birotor-controller.service \
            /usr/lib/systemd/system/birotor-sim.service \
            /usr/share/birotor/config/estimator.yaml /usr/share/birotor/config/scenarios/hover.yaml \
            /usr/share/birotor/lcmtypes/force_estimate_t.lcm /usr/share/birotor/lcmtypes/estimator_status_t.lcm \
            /usr/share/java/birotor_lcmtypes.jar /usr/bin/birotor-review /usr/bin/birotor-export \
            /usr/lib/python3/dist-packages/birotor/__init__.py /usr/lib/python3/dist-packages/birotor/log_reader.py \
            /usr/lib/python3/dist-packages/birotor/force_estimate_t.py \
            /usr/lib/python3/dist-packages/birotor/lcmtypes/force_estimate_t.lcm \
            /usr/share/doc/birotor/copyright /usr/share/doc/birotor/changelog.gz; do
  grep -qxF "$path" "$work/contents.txt" || fail "the package lacks $path"
done
for lcm_file in "$source_dir"/lcmtypes/*.lcm; do
  grep -qxF "/usr/share/birotor/lcmtypes/$(basename "$lcm_file")" "$work/contents.txt" \
    || fail "the package lacks $(basename "$lcm_file")"
done
if grep -v -e '^/usr/' -e '^/etc/birotor' -e '^/etc/default/birotor$' -e '^/etc/$' -e '^/etc/default/$' -e '^/$' \
     "$work/contents.txt" > "$work/outside.txt"; then
  fail "files outside /usr and /etc/birotor: $(tr '\n' ' ' < "$work/outside.txt")"
fi
programs=$(grep -c '^/usr/bin/.' "$work/contents.txt")
for program in $(sed -n 's|^/usr/bin/\(.\)|\1|p' "$work/contents.txt"); do
  grep -qxF "/usr/share/man/man1/$program.1.gz" "$work/contents.txt" || fail "no manual page for $program"
done
echo "ok: $(grep -vc '/$' "$work/contents.txt") files, every program (and its manual page: $programs), unit, site file, .lcm file and the jar"

# 2b. What a distribution checks: lintian finds no error (the warnings it
# prints are listed in docs/deploy.md), the changelog is this version's.
lintian --fail-on error --tag-display-limit 0 "$deb" > "$work/lintian.txt" 2>&1 || fail "lintian: $(cat "$work/lintian.txt")"
echo "ok: lintian, no error; $(grep -c '^[WIP]:' "$work/lintian.txt" || true) warnings/notes"

# 3. Conffiles and maintainer scripts.
dpkg-deb -e "$deb" "$work/control"
printf '%s\n' /etc/birotor/estimator.yaml /etc/birotor/controller.yaml /etc/birotor/identification.yaml \
  /etc/birotor/reference_vehicle.yaml /etc/default/birotor > "$work/conffiles.expected"
diff "$work/conffiles.expected" "$work/control/conffiles" > /dev/null \
  || fail "conffiles: $(tr '\n' ' ' < "$work/control/conffiles")"
for script in postinst prerm postrm; do
  [ -x "$work/control/$script" ] || fail "no executable $script"
  sh -n "$work/control/$script" || fail "$script does not parse"
done
grep -q "daemon-reload" "$work/control/postinst" || fail "postinst does not reload systemd"
grep -q "deb-systemd-invoke stop" "$work/control/prerm" || fail "prerm does not stop the daemons"
# (Quoted text, the message naming the command for the operator, left out.)
if sed 's/"[^"]*"//g' "$work/control/postinst" | grep -qE "(systemctl|deb-systemd-invoke) +(try-|reload-or-)?restart"; then
  fail "postinst restarts running daemons on upgrade (issue 39: a message instead)"
fi
grep -q "/var/lib/private/birotor" "$work/control/postrm" || fail "postrm purge leaves the state directory"
# Without systemd running (this machine, a chroot) the scripts do nothing and succeed.
[ -d /run/systemd/system ] || { DPKG_ROOT="$work/hostroot" sh "$work/control/postinst" configure > /dev/null && sh "$work/control/prerm" remove \
  && sh "$work/control/postrm" remove; } || fail "a maintainer script failed without systemd"
# The site key (issue 37): postinst makes it under dpkg's --root (DPKG_ROOT)
# once, 32 bytes, root-only writable and not world-readable, and keeps it.
keyroot="$work/keyroot"
DPKG_ROOT="$keyroot" sh "$work/control/postinst" configure > /dev/null || fail "postinst with DPKG_ROOT"
key="$keyroot/etc/birotor/keys/site.key"
[ "$(stat -c '%a %s %F' "$key" 2> /dev/null)" = "640 32 regular file" ] \
  || fail "site key after postinst: $(stat -c '%a %s %F' "$key" 2>&1)"
cp "$key" "$work/key.before"
DPKG_ROOT="$keyroot" sh "$work/control/postinst" configure > /dev/null || fail "postinst again"
cmp -s "$key" "$work/key.before" || fail "a second postinst replaced the site key"
echo "ok: conffiles $(wc -l < "$work/control/conffiles"), postinst/prerm/postrm, site key 0640 32 bytes kept"

# 4. Unpacked into a scratch root: the programs run there.
root="$work/root"
dpkg-deb -x "$deb" "$root"
if grep -rlF -e "$source_dir" -e "$build_dir" "$root" > "$work/named.txt"; then
  fail "packaged files name the source or build tree: $(tr '\n' ' ' < "$work/named.txt")"
fi
changelog_version="$(gzip -dc "$root/usr/share/doc/birotor/changelog.gz" | sed -n '1s/^birotor (\([^)]*\)).*/\1/p')"
[ "$changelog_version" = "$version" ] || fail "changelog.gz starts with version '$changelog_version', the package is $version"
grep -q "^state_file\|state_file: /var/lib/birotor/gauge_offsets.yaml" "$root/etc/birotor/estimator.yaml" \
  || fail "/etc/birotor/estimator.yaml keeps no gauge offsets"
bin="$root/usr/bin"
cd "$work"
export XDG_CONFIG_HOME="$work/xdg"  # no user files
for program in "$bin"/*; do
  "$program" --help > help.txt 2>&1 || fail "$(basename "$program") --help exited $?: $(head -3 help.txt)"
done
echo "ok: --help of $(ls "$bin" | wc -l) installed programs"
"$bin/birotor-sim" --scenario hover --set scenario.duration_s=2 --output hover.lcm --log-level warn \
  || fail "installed birotor-sim"
"$bin/birotor-replay" --log hover.lcm --output est.lcm --csv est.csv --log-level warn || fail "installed birotor-replay"
[ "$(wc -l < est.csv)" -gt 1900 ] || fail "birotor-replay wrote $(wc -l < est.csv) CSV lines for 2 s"
echo "ok: installed birotor-sim and birotor-replay: $(($(wc -l < est.csv) - 1)) FORCE rows"
"$bin/birotor-review" est.lcm --output est.html > est.counts || fail "installed birotor-review"
PYTHONPATH="$root/usr/lib/python3/dist-packages" "$bin/birotor-export" est.lcm --output-dir est-csv > /dev/null \
  || fail "installed birotor-export"
forces="$(PYTHONPATH="$root/usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  'import birotor; print(len(birotor.read_log("est.lcm")["BIROTOR_FORCE"]))')" || fail "installed Python package"
[ "$forces" = "$(sed -n 's/^BIROTOR_FORCE //p' est.counts)" ] && [ "$forces" = "$(($(wc -l < est-csv/BIROTOR_FORCE.csv) - 1))" ] \
  || fail "FORCE: $forces in the DataFrame, review $(cat est.counts), CSV $(wc -l < est-csv/BIROTOR_FORCE.csv) lines"
echo "ok: installed birotor-review, birotor-export and Python package: $forces FORCE each"

# 5. The units verify: copies whose /usr/bin is the scratch root's, so that
# systemd-analyze finds the programs (and this machine's targets).
mkdir "$work/verify"
for unit in "$root"/usr/lib/systemd/system/*.service; do
  sed "s|/usr/bin/|$root/usr/bin/|g" "$unit" > "$work/verify/$(basename "$unit")"
  # MANPATH: verify runs `man` on the unit's Documentation=man:... page, the package's.
  MANPATH="$root/usr/share/man" systemd-analyze verify "$work/verify/$(basename "$unit")" > verify.txt 2>&1 \
    || fail "systemd-analyze verify $(basename "$unit"): $(cat verify.txt)"
  if grep -v "^$" verify.txt | grep -q .; then fail "systemd-analyze verify $(basename "$unit"): $(cat verify.txt)"; fi
  grep -q "^ExecStart=/usr/bin/birotor-" "$unit" || fail "$(basename "$unit"): ExecStart not /usr/bin"
  if grep -q -- "^ExecStart=.*--params" "$unit"; then fail "$(basename "$unit") names --params (skips the search)"; fi
done
unit="$root/usr/lib/systemd/system/birotor-estimator.service"
for line in Type=notify WatchdogSec=5s Restart=always DynamicUser=yes StateDirectory=birotor; do
  grep -qx "$line" "$unit" || fail "birotor-estimator.service lacks $line"
done
echo "ok: systemd-analyze verify of $(ls "$root"/usr/lib/systemd/system | wc -l) units (and their manual pages)"

if [ "$(id -u)" -ne 0 ] || ! unshare -m true 2> /dev/null; then
  echo "SKIPPED: the /etc/birotor and state directory checks need root and unshare -m"
  exit 77
fi
cp "$source_dir/tests/deploy/package_daemon_check.sh" "$source_dir/tests/deploy/unit_command_line.sh" "$work/"
unshare -m --propagation private bash "$work/package_daemon_check.sh" "$work" "$root" "$port"
echo "PASS"
