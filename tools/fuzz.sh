#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang (AddressSanitizer + UBSan) into
# build-fuzz/ and runs each for a while on its seed corpus (copied, so the
# repository's corpus only changes by hand).
# Usage: tools/fuzz.sh [seconds per harness, default 60] [harness ...]
# Extra libFuzzer flags in BIROTOR_FUZZ_ARGS, e.g. "-fork=1 -ignore_crashes=1"
# to keep going after a finding and collect every distinct one.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
tools/setup.sh --no-build
BUILD_DIR="${BIROTOR_FUZZ_BUILD_DIR:-build-fuzz}"
# Every library the harnesses link is instrumented too (coverage for the
# fuzzer, ASan + UBSan for the bugs), not only the harness file itself.
SANITIZE_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined"
CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$SANITIZE_FLAGS" -DCMAKE_CXX_FLAGS="$SANITIZE_FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DBIROTOR_FUZZ=ON -DBIROTOR_BUILD_TESTS=OFF -DBIROTOR_BUILD_BENCHMARKS=OFF > "$BUILD_DIR.cmake.log" 2>&1 \
  || { cat "$BUILD_DIR.cmake.log"; exit 1; }
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
  for dir in fuzz/corpus/*/; do harnesses+=("$(basename "$dir")"); done
fi
cmake --build "$BUILD_DIR" -j "${BIROTOR_JOBS:-$(nproc)}" --target "${harnesses[@]}"
status=0
for h in "${harnesses[@]}"; do
  work="$BUILD_DIR/corpus-$h"
  mkdir -p "$work" "$BUILD_DIR/artifacts-$h"
  cp -n "fuzz/corpus/$h/"* "$work/" 2>/dev/null || true
  echo "fuzz: $h for ${seconds}s"
  if ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     "$BUILD_DIR/fuzz/$h" -max_total_time="$seconds" -rss_limit_mb=2048 -print_final_stats=1 ${BIROTOR_FUZZ_ARGS:-} \
       -artifact_prefix="$BUILD_DIR/artifacts-$h/" "$work" > "$BUILD_DIR/fuzz-$h.log" 2>&1; then
    # (|| true: with pipefail a missing line must not end the script silently.)
    runs=$(grep -E '^stat::number_of_executed_units' "$BUILD_DIR/fuzz-$h.log" | awk '{print $2}' || true)
    # -fork=1 prints no final stats; its last status line starts with "#<runs>:".
    [ -n "$runs" ] || runs=$(grep -oE '^#[0-9]+:' "$BUILD_DIR/fuzz-$h.log" | tail -1 | tr -d '#:' || true)
    echo "fuzz: $h: $runs runs, no crash, no leak, no sanitizer report"
  else
    echo "fuzz: $h FAILED; see $BUILD_DIR/fuzz-$h.log and $BUILD_DIR/artifacts-$h/"
    tail -30 "$BUILD_DIR/fuzz-$h.log"
    status=1
  fi
done
exit $status
