#!/usr/bin/env bash
# The whole test suite: install the Debian packages, then build and run every test twice,
# optimised (Release) and under AddressSanitizer + UndefinedBehaviorSanitizer.
# Long checks carry the CTest label `slow` and fuzzers the label `fuzz`; neither runs here
# (see README: Tests).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure --label-exclude 'slow|fuzz'

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBOXGEN_SANITIZE=ON -DBOXGEN_BUILD_BENCH=OFF
cmake --build build-asan -j"$jobs"
ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -j"$jobs" --output-on-failure --label-exclude 'slow|fuzz'
