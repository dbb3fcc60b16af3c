#!/usr/bin/env bash
# Hardening (issue 37): `cmake --install` into a temporary prefix, then
#  - every installed ELF program: position independent (ELF type DYN), bound
#    at start (BIND_NOW / FLAGS_1 NOW), a read-only relocation segment
#    (GNU_RELRO), the stack protector (__stack_chk_fail) and FORTIFY_SOURCE
#    (some __*_chk call) among its dynamic symbols (cmake/BirotorHardening.cmake);
#  - every unit: `systemd-analyze security --offline=true` below
#    MAX_EXPOSURE, and still allowed what the daemons need: SCHED_FIFO and
#    locked memory through LimitRTPRIO= and LimitMEMLOCK= (no RestrictRealtime=),
#    AF_INET for UDP multicast and AF_UNIX for sd_notify.
# Usage: hardening_test.sh BUILD_DIR
set -euo pipefail
build_dir="$(cd "$1" && pwd -P)"
# systemd-analyze's exposure (0 safest, 10 worst): 1.6 measured for each unit
# on 2026-12-03 (systemd 252) with deploy/unit-sandbox.conf, times 1.5; issue
# 37's target is below 5.0.
max_exposure=2.4
fail() { echo "FAIL: $*" >&2; exit 1; }
work="$(mktemp -d /tmp/birotor-hardening-XXXXXX)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log" || fail "cmake --install: $(tail "$work/install.log")"

programs=0
for program in "$work"/prefix/bin/*; do
  [ "$(head -c 4 "$program" | od -An -c | tr -d ' ')" = "177ELF" ] || continue
  name="$(basename "$program")"
  readelf -h "$program" | grep -q "Type: *DYN" || fail "$name is not position independent: $(readelf -h "$program" | grep Type:)"
  readelf -d "$program" > "$work/dynamic.txt"
  grep -qE "\(FLAGS\) +BIND_NOW|\(FLAGS_1\) +Flags:.* NOW" "$work/dynamic.txt" || fail "$name is not bound at start (-z now)"
  readelf -lW "$program" | grep -q "GNU_RELRO" || fail "$name has no GNU_RELRO segment (-z relro)"
  readelf --dyn-syms -W "$program" > "$work/symbols.txt"
  grep -q " __stack_chk_fail" "$work/symbols.txt" || fail "$name calls no __stack_chk_fail (-fstack-protector-strong)"
  grep -qE " __[a-z0-9_]+_chk(@|$)" <(grep -v __stack_chk_fail "$work/symbols.txt") \
    || fail "$name calls no fortified __*_chk function (-D_FORTIFY_SOURCE=2)"
  programs=$((programs + 1))
done
[ "$programs" -ge 12 ] || fail "only $programs ELF programs installed"
echo "ok: $programs programs are PIE with BIND_NOW, GNU_RELRO, stack protector and FORTIFY_SOURCE"

units=0
for unit in "$work"/prefix/share/birotor/deploy/*.service; do
  name="$(basename "$unit")"
  systemd-analyze security --offline=true "$unit" > "$work/security.txt" 2>&1 \
    || fail "systemd-analyze security $name: $(tail -3 "$work/security.txt")"
  exposure="$(sed -n 's/.*Overall exposure level for .*: \([0-9.]*\) .*/\1/p' "$work/security.txt")"
  [ -n "$exposure" ] || fail "no exposure level for $name: $(tail -3 "$work/security.txt")"
  awk -v e="$exposure" -v m="$max_exposure" 'BEGIN { exit !(e < m) }' || fail "$name exposure $exposure, at most $max_exposure"
  for line in LimitRTPRIO=99 LimitMEMLOCK=infinity; do
    grep -qx "$line" "$unit" || fail "$name lacks $line (SCHED_FIFO and locked memory for --realtime-priority)"
  done
  if grep -q "^RestrictRealtime=yes" "$unit"; then fail "$name forbids SCHED_FIFO (RestrictRealtime=yes)"; fi
  grep -q "^RestrictAddressFamilies=.*AF_INET .*AF_UNIX" "$unit" || fail "$name: no AF_INET and AF_UNIX sockets"
  echo "ok: $name exposure $exposure (at most $max_exposure)"
  units=$((units + 1))
done
[ "$units" -eq 3 ] || fail "$units units, expected 3"
echo "PASS"
