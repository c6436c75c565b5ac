#!/usr/bin/env bash
# The whole test suite, as CI runs it: install the Debian packages, then
#  1. build and run every test optimised (preset release, GCC);
#  2. lint: clang-format and clang-tidy on the project's own sources (scripts/lint.sh);
#  3. build and run every test under AddressSanitizer + UndefinedBehaviorSanitizer (preset asan);
#  4. build the libFuzzer targets with clang and run each for 10 seconds (preset fuzz).
# Long checks carry the CTest label `slow` and are not run here (see docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"

cmake --preset release
cmake --build --preset release -j"$jobs"
ctest --preset release -j"$jobs"

scripts/lint.sh build

cmake --preset asan
cmake --build --preset asan -j"$jobs"
ctest --preset asan -j"$jobs"

cmake --preset fuzz
cmake --build --preset fuzz -j"$jobs"
ctest --preset fuzz  # one fuzzer at a time: each gets the whole machine for its 10 s
