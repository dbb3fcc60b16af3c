#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer
# (CMake option BIROTOR_SANITIZE=ON) into build-asan/ and runs the complete
# CTest suite under them; prints the result and the wall time of each stage.
# Usage: tools/sanitize.sh [extra ctest arguments, e.g. -LE soak]
# Environment: BIROTOR_ASAN_BUILD_DIR (default build-asan), BIROTOR_JOBS.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BIROTOR_ASAN_BUILD_DIR:-build-asan}"
JOBS="${BIROTOR_JOBS:-$(nproc)}"
tools/setup.sh --no-build

start=$(date +%s)
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBIROTOR_SANITIZE=ON \
  -DBIROTOR_BUILD_BENCHMARKS=OFF > "$BUILD_DIR.cmake.log" 2>&1 || { cat "$BUILD_DIR.cmake.log"; exit 1; }
cmake --build "$BUILD_DIR" -j "$JOBS"
built=$(date +%s)

# Any sanitizer report fails the test that produced it. LeakSanitizer is on
# (the default with ASan on Linux).
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS" "$@" 2>&1 | tee "$BUILD_DIR/ctest.log" || status=$?
done_s=$(date +%s)
echo "sanitize: build $((built - start)) s, tests $((done_s - built)) s; $(grep -E 'tests passed' "$BUILD_DIR/ctest.log" || echo 'no summary')"
if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" "$BUILD_DIR/ctest.log"; then
  echo "sanitize: sanitizer reports found in $BUILD_DIR/ctest.log"
  status=1
fi
exit $status
