#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite with CTest.
# Usage: tools/test.sh [ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
BUILD_DIR="${BIROTOR_BUILD_DIR:-build}"

# The live tests publish a few thousand packets per second on loopback; give
# LCM's sockets room for bursts (README "Receive buffer"). Best effort: root only.
want=4194304
have=$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 0)
if [ "$have" -lt "$want" ]; then
  if [ "$(id -u)" -eq 0 ]; then
    sysctl -qw net.core.rmem_max=$want || echo "test.sh: note: could not raise net.core.rmem_max ($have B)"
  elif command -v sudo > /dev/null && sudo -n true 2> /dev/null; then
    sudo sysctl -qw net.core.rmem_max=$want || true
  else
    echo "test.sh: note: net.core.rmem_max is $have B; the live soak test may see drops (raise it to $want)"
  fi
fi

ctest --test-dir "$BUILD_DIR" --output-on-failure -j "${BIROTOR_JOBS:-$(nproc)}" "$@"
