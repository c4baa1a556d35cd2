#!/usr/bin/env bash
# README command 2: installs what is missing, builds everything, runs every test
# (Release build: all suites; sanitizer build, ASan + UBSan: unit, command, LCM and Python tests).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
bash tools/setup.sh

JOBS="${JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j"$JOBS"
ctest --test-dir build/release --output-on-failure -j"$JOBS"

cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=Debug -DPOOL_SANITIZE=ON \
      -DPOOL_BUILD_COMPARE=OFF >/dev/null
cmake --build build/sanitize -j"$JOBS"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build/sanitize --output-on-failure -j"$JOBS" -L 'unit|tools|lcm|python'
