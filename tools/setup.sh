#!/usr/bin/env bash
# Installs every dependency from Debian's packages (idempotent) and builds the
# project into build/. Usage: tools/setup.sh [--no-build] [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libceres-dev libgoogle-glog-dev
  liblcm-dev liblcm-bin liblcm-java libjchart2d-java libglib2.0-dev default-jdk-headless
  libspdlog-dev libfmt-dev libyaml-cpp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  help2man lintian
  gnuplot-nox clang libclang-rt-14-dev procps
  libsodium-dev libsystemd-dev libjs-dygraphs chromium python3-pandas python3-venv python3-wheel libalglib-dev stress-ng
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

[ "${1:-}" = "--no-build" ] && exit 0
BUILD_DIR="${BIROTOR_BUILD_DIR:-build}"
JOBS="${BIROTOR_JOBS:-$(nproc)}"
# A new build directory compiles with clang unless CC / CXX name another
# compiler: the same figures as GCC, about a third less compile time
# (docs/development.md). An existing directory keeps the compiler it has.
COMPILER=()
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ] && [ -z "${CXX:-}" ] && [ -z "${CC:-}" ]; then
  COMPILER=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${COMPILER[@]}" "$@" > "$BUILD_DIR.cmake.log" 2>&1 \
  || { cat "$BUILD_DIR.cmake.log"; exit 1; }
cmake --build "$BUILD_DIR" -j "$JOBS"
